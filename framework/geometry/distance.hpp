#pragma once
// Closest points between a point and a triangle and between two segments (Ericson, "Real-Time Collision
// Detection", §5.1.5 and §5.1.9), robust to degenerate input: zero-area triangles and zero-length segments
// fall back to the segment / point cases instead of dividing by zero.
#include <array>

#include "framework/geometry/vec.hpp"

namespace ccdlab {

struct PointTriangleClosest {
  double distance_sq;
  std::array<double, 3> bary;  ///< weights of a, b, c of the closest point
};

struct SegmentSegmentClosest {
  double distance_sq;
  double s;  ///< parameter on segment p (p0 + s (p1 - p0))
  double t;  ///< parameter on segment q
};

SegmentSegmentClosest closest_segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);
PointTriangleClosest closest_point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace ccdlab
