#include "strategies/testers/conservative_tester.hpp"

#include <algorithm>
#include <array>

#include "framework/geometry/distance.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

using interval_ccd::Verdict;

/// Smallest window worth splitting: t has about 53 bits in [0, 1].
constexpr double kMinWidth = 0x1p-50;

struct Window {
  double tl, th;
};

/// Depth-first stack of windows, earliest on top. Bisection depth is ≤ 50, so it never holds more than ~51.
struct WindowStack {
  std::array<Window, 64> w;
  int n = 0;
  [[nodiscard]] bool full() const { return n + 2 > int(w.size()); }
  void push(Window x) { w[n++] = x; }
  Window pop() { return w[--n]; }
  [[nodiscard]] bool empty() const { return n == 0; }
};

CcdHit with_coords(CcdHit h, const VertexFaceQuery& q) {
  auto at = [&](const Vec3& a, const Vec3& b) -> Vec3 { return a + h.toi * (b - a); };
  const auto c = closest_point_triangle(at(q.v_t0, q.v_t1), at(q.f0_t0, q.f0_t1), at(q.f1_t0, q.f1_t1), at(q.f2_t0, q.f2_t1));
  h.coords = {c.bary[1], c.bary[2]};
  return h;
}
CcdHit with_coords(CcdHit h, const EdgeEdgeQuery& q) {
  auto at = [&](const Vec3& a, const Vec3& b) -> Vec3 { return a + h.toi * (b - a); };
  const auto c = closest_segment_segment(at(q.ea0_t0, q.ea0_t1), at(q.ea1_t0, q.ea1_t1), at(q.eb0_t0, q.eb0_t1), at(q.eb1_t0, q.eb1_t1));
  h.coords = {c.s, c.t};
  return h;
}

}  // namespace

ConservativeTester::Fallback ConservativeTester::parse_fallback(const std::string& name) {
  if (name == "hit") return Fallback::hit;
  if (name == "exact") return Fallback::exact;
  fail("tester.fallback: expected 'hit' or 'exact', got '{}'", name);
}

double ConservativeTester::earliest_root(const interval_ccd::RelativeMotion& m, double tl, double th) const {
  WindowStack stack;
  stack.push({tl, th});
  while (!stack.empty()) {
    const Window w = stack.pop();
    if (interval_ccd::classify(m, w.tl, w.th, /*coplanarity_only=*/true) == Verdict::separated) continue;
    if (w.th - w.tl <= std::max(params_.toi_tolerance, kMinWidth) || stack.full()) return w.tl;
    const double mid = 0.5 * (w.tl + w.th);
    stack.push({mid, w.th});
    stack.push({w.tl, mid});
  }
  return tl;  // unreachable in exact arithmetic (a root was proven in [tl, th]); tl is still a lower bound
}

template <class Query>
CcdHit ConservativeTester::search(const Query& q) const {
  const interval_ccd::RelativeMotion m = interval_ccd::relative_motion(q);
  // Width at which a window counts as resolved: the features move at most δ·L within it.
  const double min_width = m.motion > 0 ? std::max(params_.delta * m.extent / m.motion, kMinWidth) : 1.0;
  auto undecided = [&](double tl, double th) {
    CcdHit h;
    if (params_.fallback == Fallback::exact) {
      const ExactTester::Decision d = exact_.decide(q);
      h.hit = d.hit;
      h.toi = d.toi_lo;
    } else {
      // Any contact needs f = 0, so the earliest window where f may vanish still bounds the time from below.
      h.hit = true;
      h.toi = earliest_root(m, tl, th);
    }
    h.route = TestRoute::fallback;
    return h.hit ? with_coords(h, q) : h;
  };
  WindowStack stack;
  stack.push({0.0, 1.0});
  int visited = 0;
  while (!stack.empty()) {
    const Window w = stack.pop();
    if (++visited > params_.max_windows) return undecided(w.tl, w.th);
    switch (interval_ccd::classify(m, w.tl, w.th)) {
      case Verdict::separated:
        continue;
      case Verdict::contact: {
        CcdHit h;
        h.hit = true;
        h.toi = earliest_root(m, w.tl, w.th);
        return with_coords(h, q);
      }
      case Verdict::unknown:
        if (w.th - w.tl <= min_width || stack.full()) return undecided(w.tl, w.th);
        const double mid = 0.5 * (w.tl + w.th);
        stack.push({mid, w.th});
        stack.push({w.tl, mid});
    }
  }
  return {};
}

CcdHit ConservativeTester::vertex_face(const VertexFaceQuery& q) const { return search(q); }
CcdHit ConservativeTester::edge_edge(const EdgeEdgeQuery& q) const { return search(q); }

}  // namespace ccdlab
