#pragma once
// Stage 2 of the batched narrow phase: a certified plane test over whole batches, in SIMD (Google Highway,
// dispatched at run time to the best target the CPU has: AVX-512, AVX2, SSE4 or plain 128-bit emulation).
//
// Both elementary tests watch four moving points through f(t) = A(t)·(B(t)×C(t)) (Provot 1997):
//   VF: A = v − f0, B = f1 − f0, C = f2 − f0        |f| / |B×C| = distance of v to the face's plane
//   EE: A = b0 − a0, B = a1 − a0, C = b1 − b0       |f| / |B×C| = distance between the two edges' lines
// The plane (line) distance is at most the feature distance, and |B(t)×C(t)| ≤ B̄·C̄ with B̄ = max(|B0|, |B1|)
// (the norm is convex along the linear motion), so a contact within distance r at time t needs
// |f(t)| ≤ r·B̄·C̄. Under linear motion f is a cubic whose Bernstein coefficients on [0, 1] are
//   b0 = [A0 B0 C0],  3·b1 = [A1 B0 C0] + [A0 B1 C0] + [A0 B0 C1],  3·b2 = [A0 B1 C1] + [A1 B0 C1] + [A1 B1 C0],
//   b3 = [A1 B1 C1]   ([X Y Z] = X·(Y×Z)),
// and f(t) lies between their min and max (Tang, Manocha & Tong 2010, "deforming non-penetration filters";
// with r > 0 it also covers thickness). When all four exceed r·B̄·C̄ plus their forward rounding error
// (|error| ≤ 32u·‖A‖₁‖B‖₁‖C‖₁, u = 2⁻⁵³: inputs rounded once, eight 3×3 determinants, two sums), or all lie
// below its negative, no point of the two features ever comes within r: the pair is dropped, proven.
// r is the tester's reach (PrimitiveTester::cull_reach): the farthest it could ever report a hit.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/swept/frame_points.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

/// The coordinates of a batch of feature pairs, one column per coordinate (structure of arrays).
class PlaneBatch {
 public:
  enum Column { A0x, A0y, A0z, A1x, A1y, A1z, B0x, B0y, B0z, B1x, B1y, B1z, C0x, C0y, C0z, C1x, C1y, C1z, Dx, Dy, Dz, kColumns };
  /// Columns hold at least this many doubles beyond the last row (the widest vector, AVX-512, is 8), so a
  /// kernel may load a full vector at any row below size() — stage 3 starts its EE rows at any index.
  static constexpr std::size_t kPad = 8;

  void resize(std::size_t n);
  [[nodiscard]] std::size_t size() const { return size_; }
  /// Row i: A, B, C at t0 and t1, and D = how far the origin point (f0 or a0) moves over the step. The eight
  /// points lie within 2·(‖D‖₁ + max‖A‖₁ + max‖B‖₁ + max‖C‖₁) of each other: the bound on the pair's extent L
  /// that the kernel uses for the tester's relative reach (an overestimate only widens the reach).
  void set(std::size_t i, const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const Vec3& c0,
           const Vec3& c1, const Vec3& d) {
    const Vec3* v[7] = {&a0, &a1, &b0, &b1, &c0, &c1, &d};
    for (int k = 0; k < 7; ++k)
      for (int j = 0; j < 3; ++j) col_[3 * k + j][i] = (*v[k])[j];
  }
  [[nodiscard]] const double* column(int c) const { return col_[c].data(); }
  [[nodiscard]] double* column(int c) { return col_[c].data(); }

  /// What plane_filter leaves per row for stage 3 (split_filter.hpp): the cubic's Bernstein coefficients
  /// (b1, b2 times 3), the threshold they were compared with, and the reach.
  enum Result { Q0, Q1x3, Q2x3, Q3, Threshold, Reach, kResults };
  [[nodiscard]] double result(int r, std::size_t i) const { return out_[r][i]; }
  [[nodiscard]] double* result_column(int r) { return out_[r].data(); }
  [[nodiscard]] const double* result_column(int r) const { return out_[r].data(); }
  /// Keeps the rows whose keep flag is set (inputs and results), in order; returns the new size.
  std::size_t compact(const std::uint8_t* keep);

 private:
  // Uninitialized on growth: set() writes every row, resize() the padding.
  std::array<UninitializedVector<double>, kColumns> col_;
  std::array<UninitializedVector<double>, kResults> out_;
  UninitializedVector<std::size_t> kept_;  ///< compact's scratch
  std::size_t size_ = 0;
};

/// Stage 2's staging: writes rows [first, first + pairs.size()) of `batch` (sized already) from the pairs'
/// positions (`points`, the step's frames: frame_points.hpp), in SIMD where the CPU has 256-bit vectors (four
/// rows at a time, each point's coordinates loaded and transposed; the plain loop was bound by its ~90
/// instructions a row, not by memory). The same doubles as set() with, for VF (v, f): A = v − f0, B = f1 − f0,
/// C = f2 − f0, D = f0(t1) − f0(t0); for EE (a, b): A = b0 − a0, B = a1 − a0, C = b1 − b0, D = a0(t1) − a0(t0)
/// (A, B, C at t0 and t1).
void stage_vf_rows(PlaneBatch& batch, std::size_t first, std::span<const VertexFacePair> pairs, const Face* faces,
                   const FramePoints* points);
void stage_ee_rows(PlaneBatch& batch, std::size_t first, std::span<const EdgeEdgePair> pairs, const Edge* edges,
                   const FramePoints* points);

/// keep[i] = 0 when pair i is proven to stay farther than the reach, 1 otherwise (keep has batch.size()
/// entries); fills the batch's results. Runs on the best SIMD target of this CPU (or the one forced by hwy::SetSupportedTargetsForTest).
void plane_filter(PlaneBatch& batch, CullReach reach, std::uint8_t* keep);

/// The same test for one pair, plain C++: the reference the SIMD targets are checked against.
[[nodiscard]] bool plane_filter_keeps(const PlaneBatch& batch, std::size_t i, CullReach reach);

}  // namespace ccdlab
