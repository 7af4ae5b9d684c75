#include "framework/sim/quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/geometry/distance.hpp"

namespace ccdlab {
namespace {

double orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return (b - a).cross(c - a).dot(d - a); }

/// Segment p–q against triangle a b c (not coplanar): crosses or touches it.
bool segment_hits_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
  if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || (sp == 0 && sq == 0)) return false;
  const double u = orient(p, q, a, b), v = orient(p, q, b, c), w = orient(p, q, c, a);
  return (u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0);
}

}  // namespace

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  const std::array<Vec3, 3> a{a0, a1, a2}, b{b0, b1, b2};
  for (int i = 0; i < 3; ++i) {
    if (segment_hits_triangle(a[i], a[(i + 1) % 3], b0, b1, b2)) return true;
    if (segment_hits_triangle(b[i], b[(i + 1) % 3], a0, a1, a2)) return true;
  }
  // Coplanar triangles: the segment test does not see them; they overlap when they are at distance zero.
  const Vec3 n = (a1 - a0).cross(a2 - a0);
  if (std::abs(n.dot(b0 - a0)) + std::abs(n.dot(b1 - a0)) + std::abs(n.dot(b2 - a0)) == 0)
    return triangle_distance(a0, a1, a2, b0, b1, b2) == 0;
  return false;
}

double triangle_distance(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  const std::array<Vec3, 3> a{a0, a1, a2}, b{b0, b1, b2};
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, closest_point_triangle(a[i], b0, b1, b2).distance_sq);
    best = std::min(best, closest_point_triangle(b[i], a0, a1, a2).distance_sq);
    for (int j = 0; j < 3; ++j)
      best = std::min(best, closest_segment_segment(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]).distance_sq);
  }
  return std::sqrt(best);
}

QualityMeter::QualityMeter(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies, double thickness)
    : mesh_(mesh), thickness_(thickness),
      pipeline_(std::make_unique<CcdPipeline>(mesh, std::move(bodies), std::move(strategies))) {}

FrameQuality QualityMeter::measure(const Positions& x) {
  pipeline_->step(x, x);  // the broad phase of a step from the frame to itself: face pairs within the thickness
  FrameQuality q;
  for (const FacePair& pair : pipeline_->last_candidates().pairs) {
    const auto& fa = mesh_.face(pair.a);
    const auto& fb = mesh_.face(pair.b);
    bool shared = false;
    for (Index u : fa)
      for (Index w : fb) shared |= u == w;
    if (shared) continue;  // a common vertex (not adjacent by an edge): touching there is not an intersection
    ++q.candidate_pairs;
    const Vec3 &a0 = x[std::size_t(fa[0])], &a1 = x[std::size_t(fa[1])], &a2 = x[std::size_t(fa[2])];
    const Vec3 &b0 = x[std::size_t(fb[0])], &b1 = x[std::size_t(fb[1])], &b2 = x[std::size_t(fb[2])];
    if (triangles_intersect(a0, a1, a2, b0, b1, b2)) ++q.intersecting_pairs;
    else if (thickness_ > 0 && triangle_distance(a0, a1, a2, b0, b1, b2) < thickness_) ++q.close_pairs;
  }
  return q;
}

}  // namespace ccdlab
