#pragma once
// The quality of a simulated frame (what `ccdlab simulate` reports per frame): triangle pairs that intersect
// (a discrete test at the frame; the goal is zero), pairs closer than the cloth thickness, kinetic energy.
// Candidate pairs come from ccdlab's own broad phase (a CCD step from the frame to itself, volumes inflated by
// the thickness); adjacent triangles of one body are never a pair, as in CCD.
#include <cstdint>
#include <memory>

#include "framework/pipeline/ccd_pipeline.hpp"

namespace ccdlab {

/// Whether two triangles intersect (share a point), decided exactly (CGAL's exact predicates); for triangles
/// with no common vertex. Coplanar overlaps count too.
bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2);

/// Smallest distance between two triangles (the 6 vertex–face and 9 edge–edge distances).
double triangle_distance(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2);

struct FrameQuality {
  std::uint64_t intersecting_pairs = 0;
  std::uint64_t intersecting_obstacle_pairs = 0;  ///< of those, pairs with an obstacle's triangle
  std::uint64_t close_pairs = 0;  ///< closer than the thickness, not intersecting
  std::uint64_t candidate_pairs = 0;
};

class QualityMeter {
 public:
  /// `strategies` pick the broad phase (its tester's thickness sets what "close" means).
  QualityMeter(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies, double thickness);
  FrameQuality measure(const Positions& x);

 private:
  const TriMesh& mesh_;
  double thickness_;
  std::vector<char> obstacle_face_;  ///< per face: 1 when it belongs to an obstacle (not cloth)
  std::unique_ptr<CcdPipeline> pipeline_;
};

}  // namespace ccdlab
