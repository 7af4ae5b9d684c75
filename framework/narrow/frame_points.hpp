#pragma once
// The step's two frames, one 64-byte line per vertex: what the narrow phase's staging kernels read (stage 0's
// twelve corners of a candidate, stage 2's four points of a feature pair). Their reads are random, by vertex id;
// with each frame in an array of its own, every point read touched two lines, and the two loads of 24 bytes
// straddled lines besides. Filled each step by FeatureBounds::update, in its pass over the vertices.
#include <cstddef>

#include "framework/geometry/vec.hpp"

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
