#pragma once
// Stage 1 of a step (docs/pipeline.md): the swept 26-DOP of every vertex over the step, inflated by η/2, computed
// once and read by the hierarchy (its leaves, face_dop) and by the narrow phase (its feature cull,
// narrow/kdop_filter.hpp). An edge's and a face's 26-DOP are the union of their vertices' (exact: min/max of floats).
//
// Why culling by these bounds never changes the answer (the invariant that makes every representative rule, mode,
// scheduler and K report the same contacts):
//   1. A pair whose features come within η during the step passes: the 26-DOPs contain the swept features
//      (rounded outward as in kdop.hpp), and the midpoint of two points within η lies within η/2 of each.
//   2. A pair that passes has overlapping LEAF volumes for every face g incident to the first feature and h to
//      the second, whatever K the hierarchy uses: a leaf is the union of its face's three vertex 26-DOPs, on the
//      K/2 of the 26-DOP's axes that K uses (face_dop below; K = 6, 14, 18 and 26 all take theirs from the 26,
//      checked below), so it contains each of its vertices' 26-DOPs restricted to those axes. So every
//      non-adjacent (g, h) is a candidate, and the pair reaches the tester whichever face pair represents it.
//      The same η/2 suffices for the hierarchy: triangles within η have points within η/2 of one midpoint.
// Contacts are thus {tester hit} ∩ {feature 26-DOPs overlap}, a set no choice of strategy can change.
//
// Two copies of each vertex's 26-DOP:
//   - float, 13 minima then 13 maxima padded to 16 floats each (zero lanes never separate): 128 bytes, two
//     cache lines. The definition of the cull.
//   - coarse, the same bounds mapped monotonically onto a 16-bit grid per axis: 64 bytes, one cache line. It
//     keeps every pair the float test keeps (CoarseDop below), so a cull by it first drops nothing the
//     definition keeps.
#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <vector>

#include "framework/geometry/kdop.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/swept/frame_points.hpp"
#include "framework/util/parallel.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

namespace detail {
/// Where each axis of a K-DOP sits among the 26-DOP's (−1 where it is not one of them).
template <int K>
constexpr std::array<int, K / 2> axes_in_26() {
  std::array<int, K / 2> at{};
  for (std::size_t i = 0; i < at.size(); ++i) {
    at[i] = -1;
    for (std::size_t j = 0; j < KDopAxes<26>::axes.size(); ++j)
      if (KDopAxes<K>::axes[i] == KDopAxes<26>::axes[j]) at[i] = int(j);
  }
  return at;
}
template <int K>
constexpr bool axes_within_26() {
  for (int j : axes_in_26<K>())
    if (j < 0) return false;
  return true;
}
}  // namespace detail
static_assert(detail::axes_within_26<6>() && detail::axes_within_26<14>() && detail::axes_within_26<18>() &&
                  detail::axes_within_26<26>(),
              "point 2 above: the feature 26-DOP must hold every axis of every hierarchy's k-DOP, same sign");

/// A vertex's swept 26-DOP, padded for SIMD.
struct alignas(64) PaddedDop {
  static constexpr int kAxes = KDop<26>::num_axes;  // 13
  static constexpr int kLanes = 16;
  float min[kLanes];
  float max[kLanes];
};
static_assert(sizeof(PaddedDop) == 128 && PaddedDop::kAxes <= PaddedDop::kLanes);

/// A vertex's swept 26-DOP on a 16-bit grid. Axis i maps every bound x (minima and maxima alike) to
/// q_i(x) = floor((x − lo_i)·s_i − 32500), computed in float and clamped to ±32767, with lo_i, s_i spreading the
/// step's range of that axis over 65,000 steps; maxima are stored negated.
/// Never separates what the float 26-DOPs do not: every operation of q rounds monotonically, so q is monotone,
/// and q(x) > q(y) only if x > y. Unions (min of minima, min of negated maxima) commute with a monotone q.
/// Separation on axis i is q_a.min + q_b.neg_max > 0, a saturating 16-bit add: the exact difference lies within
/// ±65,534 and saturation keeps its sign. A NaN maps to the clamp that never separates (−32767 as a minimum,
/// +32767 as a maximum): the float test never separates on a NaN either. Padding lanes are 0 (0 + 0 is not > 0).
struct alignas(64) CoarseDop {
  static constexpr int kLanes = 16;
  static constexpr double kSteps = 65000.0, kOffset = 32500.0, kClamp = 32767.0;  // see above
  std::int16_t min[kLanes];
  std::int16_t neg_max[kLanes];
};
static_assert(sizeof(CoarseDop) == 64 && PaddedDop::kAxes <= CoarseDop::kLanes);

/// A vertex's swept 26-DOP over the step (the points p at t0 and q at t1), inflated by r: KDop<26>::grow then
/// inflate, padded. The plain version (compiled beside the SIMD one, vertex_dops_simd.cpp, with the same rounding
/// flags); FeatureBounds::update runs the same operations in SIMD.
PaddedDop swept_vertex_dop(const Vec3& p, const Vec3& q, double r);

namespace detail {
/// swept_vertex_dop of vertices [0, n) in SIMD (vertex_dops_simd.cpp), the same floats; a vertex with a non-finite
/// coordinate takes the plain version.
void swept_vertex_dops(const Vec3* x_t0, const Vec3* x_t1, std::size_t n, double r, PaddedDop* out);
/// The coarse copy of n float 26-DOPs (SIMD, vertex_dops_simd.cpp): per lane, g = (x − lo)·scale − offset.
void quantize_dops(const PaddedDop* in, CoarseDop* out, std::size_t n, const float* lo, const float* scale,
                   const float* offset);
}  // namespace detail

class FeatureBounds {
 public:
  /// Swept 26-DOP of every vertex between the two frames, inflated by thickness / 2 (float and coarse); and the
  /// two frames interleaved, as stage 2's staging kernel reads them (frame_points.hpp).
  void update(const Positions& x_t0, const Positions& x_t1, double thickness, int threads, PhaseTrace& trace);

  /// Vertex v at both ends of the step, v < the frames' size (update).
  [[nodiscard]] const FramePoints* frame_points() const { return points_.data(); }
  /// At least the 1-norm extent of the box of every vertex in both frames (Σ over x, y, z of its side): what bounds
  /// the size of any pair of features, for reaches relative to it (CullReach::rel).
  [[nodiscard]] double scene_extent() const { return extent_; }

  /// The swept K-DOP of a face: the union of its three vertices' 26-DOPs, on K's axes. The hierarchy's leaves
  /// are these (point 2 above); 3 × 32 floats min/max and K selections, against 6 points × K/2 projections.
  template <int K>
  [[nodiscard]] KDop<K> face_dop(const Face& f) const {
    const PaddedDop &a = vertex_[f[0]], &b = vertex_[f[1]], &c = vertex_[f[2]];
    alignas(64) float lo[PaddedDop::kLanes], hi[PaddedDop::kLanes];
#if defined(__SSE2__)
    // Four lanes per instruction, no branch: plain std::min compiles to a compare-and-branch per axis, whose
    // outcome is random from one leaf to the next.
    for (int i = 0; i < PaddedDop::kLanes; i += 4) {
      _mm_store_ps(lo + i, _mm_min_ps(_mm_min_ps(_mm_load_ps(a.min + i), _mm_load_ps(b.min + i)), _mm_load_ps(c.min + i)));
      _mm_store_ps(hi + i, _mm_max_ps(_mm_max_ps(_mm_load_ps(a.max + i), _mm_load_ps(b.max + i)), _mm_load_ps(c.max + i)));
    }
#else
    for (int i = 0; i < PaddedDop::kLanes; ++i) {
      lo[i] = std::min(std::min(a.min[i], b.min[i]), c.min[i]);
      hi[i] = std::max(std::max(a.max[i], b.max[i]), c.max[i]);
    }
#endif
    static constexpr std::array<int, K / 2> at = detail::axes_in_26<K>();
    std::array<float, K / 2> mins, maxs;
    for (std::size_t i = 0; i < at.size(); ++i) mins[i] = lo[at[i]], maxs[i] = hi[at[i]];
    return KDop<K>::from_bounds(mins, maxs);
  }

  /// Every vertex's float 26-DOP and its coarse copy, indexed by vertex id (the narrow phase's stage 1 reads them).
  [[nodiscard]] const PaddedDop* dops() const { return vertex_.data(); }
  [[nodiscard]] const CoarseDop* coarse_dops() const { return coarse_.data(); }
  /// What a step of the coarse grid is worth in distance, at least, on every axis: bounds k > 2 steps apart on
  /// an axis are at least (k − 2)·coarse_step() apart along its unit direction (the floor takes up to one step,
  /// the float rounding of q a few hundredths). 0 when no axis has a usable range.
  [[nodiscard]] double coarse_step() const { return coarse_step_; }

  static constexpr std::size_t kBytesPerVertex = sizeof(PaddedDop) + sizeof(CoarseDop) + sizeof(FramePoints);
  [[nodiscard]] std::size_t memory_bytes() const { return vertex_.size() * kBytesPerVertex; }

 private:
  struct AxisRange {  ///< per axis of the 26-DOP, the lowest minimum and highest maximum over some vertices
    float lo[PaddedDop::kAxes], hi[PaddedDop::kAxes];
    AxisRange() {
      std::fill(std::begin(lo), std::end(lo), std::numeric_limits<float>::infinity());
      std::fill(std::begin(hi), std::end(hi), -std::numeric_limits<float>::infinity());
    }
    /// Widens the range to hold the bounds mins[i] … maxs[i] of every axis (a NaN bound leaves it as it is).
    void include(const float* mins, const float* maxs) {
      for (int i = 0; i < PaddedDop::kAxes; ++i) lo[i] = std::min(lo[i], mins[i]), hi[i] = std::max(hi[i], maxs[i]);
    }
  };
  /// The coarse copy of the float 26-DOPs, on the grid of `range` (the range of all of them).
  void update_coarse(const AxisRange& range, int threads, PhaseTrace& trace);

  UninitializedVector<PaddedDop> vertex_;  // update() writes every entry: growing it zeroes nothing
  UninitializedVector<CoarseDop> coarse_;
  UninitializedVector<FramePoints> points_;
  double extent_ = 0;
  double coarse_step_ = 0;
};

/// The swept k-DOP of face f over the step: the union of its vertices' swept 26-DOPs, inflated by half the
/// thickness (FeatureBounds::face_dop: the one definition, shared by the hierarchy's leaves and the references).
template <class BV>
struct SweptFaceBv {
  const TriMesh& mesh;
  const FeatureBounds& bounds;
  BV operator()(Index f) const { return bounds.face_dop<BV::k>(mesh.face(f)); }
};

/// Faces per task wherever faces are swept or boxed: large enough to amortise a hand-out, small enough to balance.
inline constexpr std::size_t kFaceChunk = 2048;

}  // namespace ccdlab
