#include "strategies/testers/additive_tester.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "framework/geometry/distance.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

/// The four points at t = 0 and their displacements over the step, as (v, f0, f1, f2) or (ea0, ea1, eb0, eb1).
struct Points {
  std::array<Vec3, 4> x0, dx;
};

double distance(const VertexFaceQuery&, const std::array<Vec3, 4>& x) {
  return std::sqrt(closest_point_triangle(x[0], x[1], x[2], x[3]).distance_sq);
}
double distance(const EdgeEdgeQuery&, const std::array<Vec3, 4>& x) {
  return std::sqrt(closest_segment_segment(x[0], x[1], x[2], x[3]).distance_sq);
}
Points points(const VertexFaceQuery& q) {
  return {{q.v_t0, q.f0_t0, q.f1_t0, q.f2_t0}, {q.v_t1 - q.v_t0, q.f0_t1 - q.f0_t0, q.f1_t1 - q.f1_t0, q.f2_t1 - q.f2_t0}};
}
Points points(const EdgeEdgeQuery& q) {
  return {{q.ea0_t0, q.ea1_t0, q.eb0_t0, q.eb1_t0},
          {q.ea0_t1 - q.ea0_t0, q.ea1_t1 - q.ea1_t0, q.eb0_t1 - q.eb0_t0, q.eb1_t1 - q.eb1_t0}};
}

/// How fast the features can approach, with the mean displacement removed: a point of the vertex (edge a)
/// moves at most the largest of its side's displacements, a point of the face (edge b) likewise.
double approach_bound(bool edge_edge, std::array<Vec3, 4> dx) {
  const Vec3 mean = 0.25 * (dx[0] + dx[1] + dx[2] + dx[3]);
  std::array<double, 4> n;
  for (std::size_t k = 0; k < 4; ++k) n[k] = (dx[k] - mean).norm();
  return edge_edge ? std::max(n[0], n[1]) + std::max(n[2], n[3]) : n[0] + std::max({n[1], n[2], n[3]});
}

template <class Query>
CcdHit search(const Query& q, const AdditiveTester::Params& p) {
  const Points pts = points(q);
  const auto at = [&](double t) {
    std::array<Vec3, 4> x;
    for (std::size_t k = 0; k < 4; ++k) x[k] = pts.x0[k] + t * pts.dx[k];
    return x;
  };
  const auto hit = [&](double t, TestRoute route) {
    CcdHit h;
    h.hit = true;
    h.toi = t;
    h.coords = contact_coords(q, t);
    h.route = route;
    return h;
  };
  const double xi = p.thickness;
  double gap = distance(q, pts.x0) - xi;
  if (!(gap > 0)) return hit(0.0, TestRoute::main);  // within ξ at the start (or NaN: never a silent miss)
  const double lp = approach_bound(std::is_same_v<Query, EdgeEdgeQuery>, pts.dx);
  if (!(lp > 0)) return {};  // a common translation: the distance stays what it is
  const double stop = (1 - p.eta) * gap;
  double t = 0, step = p.eta * gap / lp;
  for (int i = 0; i < p.max_iterations; ++i) {
    const double next = t + step;
    if (next > 1) return {};
    gap = distance(q, at(next)) - xi;
    // The first step is kept whatever it closes (as in the paper); within ξ (or NaN) nothing more is safe.
    if (!(gap > 0) || (i > 0 && gap < stop)) return hit(t, TestRoute::main);
    t = next;
    step = p.eta * gap / lp;
  }
  return hit(t, TestRoute::fallback);
}

}  // namespace

AdditiveTester::AdditiveTester(Params p) : params_(p) {
  if (!(params_.eta > 0 && params_.eta < 1)) fail("tester.eta: expected a fraction in (0, 1), got {}", params_.eta);
  if (!(params_.thickness >= 0) || !std::isfinite(params_.thickness))
    fail("tester.thickness: expected a finite distance >= 0, got {}", params_.thickness);
  if (params_.max_iterations < 1) fail("tester.max_iterations: expected at least 1, got {}", params_.max_iterations);
}

CcdHit AdditiveTester::vertex_face(const VertexFaceQuery& q) const { return search(q, params_); }
CcdHit AdditiveTester::edge_edge(const EdgeEdgeQuery& q) const { return search(q, params_); }

}  // namespace ccdlab
