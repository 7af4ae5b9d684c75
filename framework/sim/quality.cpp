#include "framework/sim/quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include "framework/geometry/distance.hpp"

namespace ccdlab {

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  // Exact predicates (CGAL's filtered kernel): cloth strips are often exactly coplanar (a cone's triangles
  // between two rulings lie in one plane), where floating-point orientation signs are noise.
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  auto p = [](const Vec3& v) { return K::Point_3(v.x(), v.y(), v.z()); };
  return CGAL::do_intersect(K::Triangle_3(p(a0), p(a1), p(a2)), K::Triangle_3(p(b0), p(b1), p(b2)));
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
    : mesh_(mesh), thickness_(thickness), obstacle_face_(std::size_t(mesh.num_faces()), 0) {
  for (const Body& b : bodies)
    if (b.kind != BodyKind::cloth) std::fill(obstacle_face_.begin() + b.face_begin, obstacle_face_.begin() + b.face_end, 1);
  pipeline_ = std::make_unique<CcdPipeline>(mesh, std::move(bodies), std::move(strategies));
  pipeline_->keep_candidates(true);  // measure() reads them
}

FrameQuality QualityMeter::measure(const Positions& x) {
  pipeline_->step(x, x);  // the broad phase of a step from the frame to itself: face pairs within the thickness
  FrameQuality q;
  for (const FacePair& pair : pipeline_->last_candidates().pairs.flatten()) {
    const auto& fa = mesh_.face(pair.a);
    const auto& fb = mesh_.face(pair.b);
    bool shared = false;
    for (Index u : fa)
      for (Index w : fb) shared |= u == w;
    if (shared) continue;  // a common vertex (not adjacent by an edge): touching there is not an intersection
    ++q.candidate_pairs;
    const Vec3 &a0 = x[std::size_t(fa[0])], &a1 = x[std::size_t(fa[1])], &a2 = x[std::size_t(fa[2])];
    const Vec3 &b0 = x[std::size_t(fb[0])], &b1 = x[std::size_t(fb[1])], &b2 = x[std::size_t(fb[2])];
    if (triangles_intersect(a0, a1, a2, b0, b1, b2)) {
      ++q.intersecting_pairs;
      q.intersecting_obstacle_pairs += obstacle_face_[std::size_t(pair.a)] | obstacle_face_[std::size_t(pair.b)];
    }
    else if (thickness_ > 0 && triangle_distance(a0, a1, a2, b0, b1, b2) < thickness_) ++q.close_pairs;
  }
  return q;
}

}  // namespace ccdlab
