#include "strategies/testers/conservative_tester.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "framework/geometry/distance.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

using interval_ccd::Verdict;

/// Smallest window worth splitting: t has about 53 bits in [0, 1].
constexpr double kMinWidth = 0x1p-50;
/// Width to which roots of f are isolated (f only) before the inside / crossing conditions are examined.
constexpr double kIsolationWidth = 0x1p-6;
/// More isolated windows than this means f is near zero over much of the step (coplanar motion).
constexpr int kMaxIsolatedWindows = 6;

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

/// A witness that the features come within `reach` of each other: at time t, the closest points found in
/// double are within `reach` once their rounding is accounted for. Each point computed (the vertices at t, then
/// a point of the face or of each edge from the computed weights) is within a few u·M of a point of its feature,
/// M the largest coordinate of the query; 256·u·M bounds the distance's error with a wide margin. When it holds,
/// no search can prove the features farther than `reach` all step.
template <class Query>
bool certainly_within_at(const Query& q, double t, double reach) {
  const auto at = [t](const Vec3& a, const Vec3& b) -> Vec3 { return a + t * (b - a); };
  double distance_sq = 0, largest = 0;
  if constexpr (std::is_same_v<Query, VertexFaceQuery>) {
    for (const Vec3* p : {&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1})
      largest = std::max(largest, p->cwiseAbs().maxCoeff());
    distance_sq = closest_point_triangle(at(q.v_t0, q.v_t1), at(q.f0_t0, q.f0_t1), at(q.f1_t0, q.f1_t1), at(q.f2_t0, q.f2_t1))
                      .distance_sq;
  } else {
    for (const Vec3* p : {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1})
      largest = std::max(largest, p->cwiseAbs().maxCoeff());
    distance_sq = closest_segment_segment(at(q.ea0_t0, q.ea0_t1), at(q.ea1_t0, q.ea1_t1), at(q.eb0_t0, q.eb0_t1),
                                          at(q.eb1_t0, q.eb1_t1))
                      .distance_sq;
  }
  return std::sqrt(distance_sq) * (1 + 0x1p-50) + 256 * 0x1p-53 * largest <= reach;  // false for NaN
}

template <class Query>
CcdHit with_coords(CcdHit h, const Query& q) {
  h.coords = contact_coords(q, h.toi);
  return h;
}

}  // namespace

ConservativeTester::ConservativeTester(Params p) : params_(p) {
  if (!(params_.thickness >= 0) || !std::isfinite(params_.thickness))
    fail("tester.thickness: expected a finite distance >= 0, got {}", params_.thickness);
  if (params_.thickness > 0 && params_.fallback == Fallback::exact)
    fail("tester.fallback: 'exact' decides contact at zero distance only; with thickness {} use fallback 'hit'", params_.thickness);
}

separation::Params ConservativeTester::separation_params() const {
  return {params_.thickness, params_.delta, params_.max_boxes, params_.toi_tolerance};
}

template <class Query>
bool ConservativeTester::may_come_close(const Query& q, double L, double t_hint) const {
  separation::Params p = separation_params();
  p.thickness = std::max(2 * params_.delta, 0.5 * kReachFloor) * L;
  if (!(p.thickness > 0)) return true;  // all eight points in one place
  // Where they touch, a witness at the undecided window answers at once; the search would find the same.
  if (certainly_within_at(q, t_hint, p.thickness)) return true;
  if constexpr (std::is_same_v<Query, VertexFaceQuery>) return separation::vertex_face(q, p).hit;
  else return separation::edge_edge(q, p).hit;
}

ConservativeTester::Fallback ConservativeTester::parse_fallback(const std::string& name) {
  if (name == "hit") return Fallback::hit;
  if (name == "exact") return Fallback::exact;
  fail("tester.fallback: expected 'hit' or 'exact', got '{}'", name);
}

double ConservativeTester::earliest_root(const interval_ccd::RelativeMotion& m, double tl, double th) const {
  const double t = interval_ccd::earliest_coplanarity(m, tl, th, std::max(params_.toi_tolerance, kMinWidth));
  return t < th ? t : tl;  // f ≠ 0 throughout cannot happen where a root was proven; tl stays a lower bound
}

template <class Query>
CcdHit ConservativeTester::search(const Query& q) const {
  const interval_ccd::Coplanarity screen = interval_ccd::screen_coplanarity(q);
  if (screen == interval_ccd::Coplanarity::never) return {};
  const interval_ccd::RelativeMotion m = interval_ccd::relative_motion(q);
  // Width at which a window counts as resolved: the features move at most δ·L within it.
  const double min_width = m.motion > 0 ? std::max(params_.delta * m.extent / m.motion, kMinWidth) : 1.0;
  auto undecided = [&](double tl, double th) {
    CcdHit h;
    if (params_.fallback == Fallback::exact) {
      const ExactTester::Decision d = exact_.decide(q);
      h.hit = d.hit;
      h.toi = d.toi_lo;
    } else if (may_come_close(q, m.extent, 0.5 * (tl + th))) {
      // Any contact needs f = 0, so the earliest window where f may vanish still bounds the time from below.
      h.hit = true;
      h.toi = earliest_root(m, tl, th);
    }
    h.route = TestRoute::fallback;
    return h.hit ? with_coords(h, q) : h;
  };
  int visited = 0;
  CcdHit result;
  bool decided = false;
  // Bisects [a, b] earliest first with the full classification; true once the query is decided.
  auto bisect = [&](double a, double b) {
    WindowStack stack;
    stack.push({a, b});
    while (!stack.empty()) {
      const Window w = stack.pop();
      if (++visited > params_.max_windows) return decided = true, result = undecided(w.tl, w.th), true;
      switch (interval_ccd::classify(m, w.tl, w.th)) {
        case Verdict::separated:
          continue;
        case Verdict::contact:
          result.hit = true;
          result.toi = earliest_root(m, w.tl, w.th);
          result = with_coords(result, q);
          return decided = true;
        case Verdict::unknown:
          if (w.th - w.tl <= min_width || stack.full()) return decided = true, result = undecided(w.tl, w.th), true;
          const double mid = 0.5 * (w.tl + w.th);
          stack.push({mid, w.th});
          stack.push({w.tl, mid});
      }
    }
    return false;  // no contact in [a, b]
  };
  // Coplanar motion (f near zero all step): bisect the whole step from the top, where separating axes settle
  // features kept apart in one go.
  if (screen == interval_ccd::Coplanarity::flat) {
    bisect(0.0, 1.0);
    return decided ? result : CcdHit{};
  }
  // Otherwise coplanarity windows first (cheap, f only), earliest first; the full classification only inside
  // them. Many such windows also mean f stays small over much of the step: then bisect from the top too.
  const double isolation_width = std::max(kIsolationWidth, min_width);
  std::array<Window, kMaxIsolatedWindows> windows;
  int count = 0;
  const bool crowded = interval_ccd::for_each_coplanarity_window(m, 0.0, 1.0, isolation_width, [&](double a, double b) {
    if (count == kMaxIsolatedWindows) return true;  // stop: too many
    windows[count++] = {a, b};
    return false;
  });
  if (crowded) {
    bisect(0.0, 1.0);
  } else {
    for (int i = 0; i < count && !bisect(windows[i].tl, windows[i].th); ++i) {
    }
  }
  return decided ? result : CcdHit{};
}

template <class Query>
double ConservativeTester::tighten(const Query& q, double toi) const {
  if (params_.thickness > 0 || !(toi < 1)) return toi;
  const double t = interval_ccd::earliest_coplanarity(interval_ccd::relative_motion(q), toi, 1.0, kTightToiWidth);
  return t < 1 ? std::max(t, toi) : toi;  // f ≠ 0 proven over the rest: a fallback hit; its time stays
}

double ConservativeTester::tighten_toi(const VertexFaceQuery& q, double toi) const { return tighten(q, toi); }
double ConservativeTester::tighten_toi(const EdgeEdgeQuery& q, double toi) const { return tighten(q, toi); }

CcdHit ConservativeTester::vertex_face(const VertexFaceQuery& q) const {
  return params_.thickness > 0 ? separation::vertex_face(q, separation_params()) : search(q);
}
CcdHit ConservativeTester::edge_edge(const EdgeEdgeQuery& q) const {
  return params_.thickness > 0 ? separation::edge_edge(q, separation_params()) : search(q);
}

}  // namespace ccdlab
