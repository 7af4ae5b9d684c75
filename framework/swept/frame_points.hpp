#pragma once
// The step's two frames, one 64-byte line per vertex: what stage 2's staging kernel reads (four points of a
// feature pair). Its reads are random, by vertex id; with each frame in an array of its own, every point read
// touched two lines, and the two loads of 24 bytes straddled lines besides. Filled each step by
// FeatureBounds::update, in its pass over the vertices. Stage 0 reads a float copy of half the size (FloatFrames).
#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>

#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

/// Vertex v's x, y, z at t0, a zero, then at t1, a zero: coordinate j in frame f at double 8v + 4f + j.
struct alignas(64) FramePoints {
  double t0[4];
  double t1[4];
};
static_assert(sizeof(FramePoints) == 64, "one cache line a vertex");

/// out[v] = vertex v of both frames, for v < n.
inline void interleave_frames(const Vec3* x_t0, const Vec3* x_t1, std::size_t n, FramePoints* out) {
  for (std::size_t v = 0; v < n; ++v) {
    FramePoints& p = out[v];
    p.t0[0] = x_t0[v].x(), p.t0[1] = x_t0[v].y(), p.t0[2] = x_t0[v].z(), p.t0[3] = 0;
    p.t1[0] = x_t1[v].x(), p.t1[1] = x_t1[v].y(), p.t1[2] = x_t1[v].z(), p.t1[3] = 0;
  }
}

}  // namespace ccdlab

namespace ccdlab {

/// Vertex v of both frames in float, relative to FloatFrames::origin: x, y, z at t0, a zero, then at t1, a zero
/// (coordinate j in frame f at float 8v + 4f + j). Stage 0 reads these: half FramePoints' bytes, twice its lanes.
struct alignas(32) FloatFramePoints {
  float t0[4];
  float t1[4];
};
static_assert(sizeof(FloatFramePoints) == 32, "two vertices a cache line");

/// Face f's bounding box at each end of the step, from its float corners: lo x, y, z, a zero, hi x, y, z, a zero
/// at t0, then at t1. Stage 0's first pass reads these: one line a face instead of three corners.
struct alignas(64) FloatFaceBoxes {
  float t0[8];
  float t1[8];
};
static_assert(sizeof(FloatFaceBoxes) == 64, "one cache line a face");

/// The step's two frames in float, moved to an origin at the centre of their box (so that the rounding is
/// relative to the scene's size, not to its distance from 0). A translation moves no distance, so a separation
/// proven on the exact translated points holds for the mesh; the float copy lies within `error` of them in every
/// coordinate of every vertex, and stage 0 widens its gaps by it (triangle_filter.hpp).
struct FloatFrames {
  Vec3 origin = Vec3::Zero();
  double error = 0;  ///< ≥ |float(x − origin) − (x − origin)|, every coordinate of every vertex and frame
  UninitializedVector<FloatFramePoints> points;
  UninitializedVector<FloatFaceBoxes> boxes;  ///< per face, from `points` (exact: minima and maxima)

  /// The n vertices' float copy, then (with `face_boxes`) the faces' boxes.
  void update(const Vec3* x_t0, const Vec3* x_t1, std::size_t n, std::span<const Face> faces, bool face_boxes = true) {
    Vec3 lo = n ? x_t0[0] : Vec3::Zero(), hi = lo;
    for (std::size_t v = 0; v < n; ++v) {
      lo = lo.cwiseMin(x_t0[v]).cwiseMin(x_t1[v]);
      hi = hi.cwiseMax(x_t0[v]).cwiseMax(x_t1[v]);
    }
    origin = 0.5 * (lo + hi);
    points.resize(n);
    double radius = 0;  // the largest |q|, q = x − origin as computed
    bool finite = true;
    for (std::size_t v = 0; v < n; ++v) {
      const Vec3 q0 = x_t0[v] - origin, q1 = x_t1[v] - origin;
      FloatFramePoints& p = points[v];
      p.t0[0] = float(q0.x()), p.t0[1] = float(q0.y()), p.t0[2] = float(q0.z()), p.t0[3] = 0;
      p.t1[0] = float(q1.x()), p.t1[1] = float(q1.y()), p.t1[2] = float(q1.z()), p.t1[3] = 0;
      finite &= q0.allFinite() && q1.allFinite();
      radius = std::max(radius, std::max(q0.cwiseAbs().maxCoeff(), q1.cwiseAbs().maxCoeff()));
    }
    // |float(q) − q| ≤ 2⁻²⁴|q| and |q − (x − origin)| ≤ 2⁻⁵³|x − origin| ≤ 2⁻⁵²|q|; the factor covers this
    // product's own rounding. A non-finite coordinate makes the error non-finite, and stage 0 then culls nothing.
    error = finite ? radius * (0x1p-24 + 0x1p-52) * (1 + 0x1p-40) : std::numeric_limits<double>::infinity();
    if (!face_boxes) return;
    boxes.resize(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const FloatFramePoints &a = points[std::size_t(faces[f][0])], &b = points[std::size_t(faces[f][1])],
                             &c = points[std::size_t(faces[f][2])];
      FloatFaceBoxes& box = boxes[f];
      for (int j = 0; j < 3; ++j) {
        box.t0[j] = std::min(std::min(a.t0[j], b.t0[j]), c.t0[j]), box.t0[4 + j] = std::max(std::max(a.t0[j], b.t0[j]), c.t0[j]);
        box.t1[j] = std::min(std::min(a.t1[j], b.t1[j]), c.t1[j]), box.t1[4 + j] = std::max(std::max(a.t1[j], b.t1[j]), c.t1[j]);
      }
      box.t0[3] = box.t0[7] = box.t1[3] = box.t1[7] = 0;
    }
  }
};

}  // namespace ccdlab
