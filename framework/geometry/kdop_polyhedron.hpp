#pragma once
// The polyhedron a k-DOP bounds: the intersection of its K half-spaces d_i · x ≤ max_i and −d_i · x ≤ −min_i,
// as vertices and faces (each face a convex polygon, counter-clockwise seen from outside). For pictures
// (`ccdlab export`): an 18-DOP is drawn as the 18-faced (at most) solid it is, not as its bounding box.
//
// Vertices are the intersections of three bounding planes that satisfy every other constraint (within a
// tolerance relative to the k-DOP's size); a face is the convex hull of the vertices on its plane, ordered by
// angle around their centroid. Slabs that touch the solid only in an edge or a vertex give no face.
#include <array>
#include <span>
#include <vector>

#include "framework/geometry/kdop.hpp"

namespace ccdlab {

struct Polyhedron {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;  ///< vertex indices, counter-clockwise seen from outside
};

/// The solid bounded by slabs min_i ≤ d_i · x ≤ max_i (empty when the slabs are empty or do not intersect).
Polyhedron slab_polyhedron(std::span<const std::array<int, 3>> axes, std::span<const float> min,
                           std::span<const float> max);

template <int K>
Polyhedron kdop_polyhedron(const KDop<K>& bv) {
  std::array<float, K / 2> lo, hi;
  for (int i = 0; i < K / 2; ++i) lo[i] = bv.min(i), hi[i] = bv.max(i);
  return slab_polyhedron(KDop<K>::axes, lo, hi);
}

}  // namespace ccdlab
