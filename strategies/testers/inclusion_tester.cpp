#include "strategies/testers/inclusion_tester.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "framework/util/error.hpp"
#include "strategies/testers/gap_boxes.hpp"

namespace ccdlab {
namespace {

using gap::Box;

/// The search over [t_from, 1] × the (u, v) square; returns the start of the accepted box, or 2 when every box
/// was discarded. With `time_width` > 0 (the earliest-time query's refinement) a box is accepted only once it
/// spans at most that much time and F moves 4 times more along t than along u and v across it: the time, not δ, is
/// then what is resolved (near a contact F's distance from 0 grows with the time before it).
template <class Query>
double earliest_box(const Query& q, const InclusionTester::Params& p, double t_from, double time_width, bool* fallback) {
  const gap::Motion m = gap::Motion::of(q);
  const double err = gap::value_error(m.M), resolved = p.delta * m.L;
  thread_local std::vector<Box> heap;
  heap.clear();
  const auto later = [](const Box& a, const Box& b) { return a.t0 > b.t0; };
  const auto push = [&](const Box& b) {
    heap.push_back(b);
    std::push_heap(heap.begin(), heap.end(), later);
  };
  push({t_from, 1, 0, 1, 0, 1});
  for (int examined = 0; !heap.empty(); ++examined) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const Box b = heap.back();
    heap.pop_back();
    if (examined == p.max_boxes) return *fallback = true, b.t0;
    const std::array<Vec3, 8> F = gap::corners(m, b);
    if (gap::excluded_by_axes(F, err, p.min_separation)) continue;
    const std::array<double, 3> move = gap::movement(F);
    const double tw = b.t1 - b.t0;
    int d = int(std::max_element(move.begin(), move.end()) - move.begin());  // halve where F moves most
    if (time_width <= 0) {
      if (std::max({move[0], move[1], move[2]}) <= resolved) return b.t0;
    } else if (tw <= time_width) {
      if (4 * std::max(move[1], move[2]) <= std::max(move[0], 16 * err)) return b.t0;
      d = move[1] >= move[2] ? 1 : 2;
    }
    const double width = d == 0 ? tw : d == 1 ? b.u1 - b.u0 : b.v1 - b.v0;
    if (width <= gap::kMinWidth) return *fallback = true, b.t0;  // no variable left to split: undecided
    Box lo = b, hi = b;
    if (d == 0) lo.t1 = hi.t0 = 0.5 * (b.t0 + b.t1);
    else if (d == 1) lo.u1 = hi.u0 = 0.5 * (b.u0 + b.u1);
    else lo.v1 = hi.v0 = 0.5 * (b.v0 + b.v1);
    push(lo);
    push(hi);
  }
  return 2.0;
}

template <class Query>
CcdHit search(const Query& q, const InclusionTester::Params& p) {
  bool fallback = false;
  const double t = earliest_box(q, p, 0.0, 0.0, &fallback);
  if (t > 1) return {};
  CcdHit h;
  h.hit = true;
  h.toi = t;
  h.coords = contact_coords(q, t);
  h.route = fallback ? TestRoute::fallback : TestRoute::main;
  return h;
}

template <class Query>
double tighten(const Query& q, const InclusionTester::Params& p, double toi) {
  // No contact before toi (a lower bound): the search restarted there, with boxes at most kTightToiWidth long in
  // time, still never passes over one.
  bool fallback = false;
  const double t = earliest_box(q, p, toi, kTightToiWidth, &fallback);
  return t <= 1 ? std::max(t, toi) : toi;
}

}  // namespace

InclusionTester::InclusionTester(Params p) : params_(p) {
  if (!(params_.delta >= 0) || !std::isfinite(params_.delta)) fail("tester.delta: expected a finite value >= 0, got {}", params_.delta);
  if (!(params_.min_separation >= 0) || !std::isfinite(params_.min_separation))
    fail("tester.min_separation: expected a finite distance >= 0, got {}", params_.min_separation);
  if (params_.max_boxes < 1) fail("tester.max_boxes: expected at least 1, got {}", params_.max_boxes);
}

CcdHit InclusionTester::vertex_face(const VertexFaceQuery& q) const { return search(q, params_); }
CcdHit InclusionTester::edge_edge(const EdgeEdgeQuery& q) const { return search(q, params_); }
double InclusionTester::tighten_toi(const VertexFaceQuery& q, double toi) const { return tighten(q, params_, toi); }
double InclusionTester::tighten_toi(const EdgeEdgeQuery& q, double toi) const { return tighten(q, params_, toi); }

}  // namespace ccdlab
