#pragma once
// Vector types: positions are double precision 3-vectors (Eigen). A frame of a mesh is a Positions array,
// indexed by vertex id.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace ccdlab {

using Vec3 = Eigen::Vector3d;
using Positions = std::vector<Vec3>;

/// Axis-aligned box in double precision; empty when lo > hi.
struct Box3 {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void grow(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const Box3& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  [[nodiscard]] Vec3 center() const { return 0.5 * (lo + hi); }
  [[nodiscard]] Vec3 extent() const { return hi - lo; }
  /// Closed-interval overlap: touching boxes overlap (contact at zero distance must not be culled).
  [[nodiscard]] bool overlaps(const Box3& b) const {
    return lo.x() <= b.hi.x() && b.lo.x() <= hi.x() && lo.y() <= b.hi.y() && b.lo.y() <= hi.y() &&
           lo.z() <= b.hi.z() && b.lo.z() <= hi.z();
  }
  void inflate(double r) {
    lo.array() -= r;
    hi.array() += r;
  }
};

}  // namespace ccdlab
