#pragma once
// The lane-pair walk in AVX2: its pair visit (visit_lane_pairs: two 8-lane compares per axis, table permutations
// for the compress-stores) and, from lane_pair_walk-inl.hpp, the walk that calls it, compiled with the AVX2
// function attribute.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "framework/traversal/bvtt_view.hpp"
#include "framework/traversal/wide_overlap.hpp"
#include "framework/traversal/lane_pair_stack.hpp"

namespace ccdlab {

#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
namespace detail {
/// Lane permutations that pack the set lanes of a mask to the front, in order: per 8-bit mask over eight 32-bit
/// lanes, and per 4-bit mask over four 64-bit lanes (as pairs of 32-bit lanes). The AVX2 visit's compress-stores.
struct CompressTable {
  alignas(32) std::array<std::array<std::int32_t, 8>, 256> lanes{};
};
constexpr CompressTable compress_32x8() {
  CompressTable t{};
  for (unsigned m = 0; m < 256; ++m)
    for (unsigned j = 0, k = 0; j < 8; ++j)
      if ((m >> j) & 1u) t.lanes[m][k++] = std::int32_t(j);
  return t;
}
constexpr CompressTable compress_64x4() {
  CompressTable t{};
  for (unsigned m = 0; m < 16; ++m)
    for (unsigned j = 0, k = 0; j < 4; ++j)
      if ((m >> j) & 1u) t.lanes[m][k] = std::int32_t(2 * j), t.lanes[m][k + 1] = std::int32_t(2 * j + 1), k += 2;
  return t;
}
inline constexpr CompressTable kCompress32x8 = compress_32x8();
inline constexpr CompressTable kCompress64x4 = compress_64x4();
}  // namespace detail

namespace lane_pair_avx2 {
// The visit's helpers (functions, not lambdas: GCC does not give a lambda its enclosing function's target).
#define CCDLAB_AVX2_INLINE CCDLAB_AVX2_TARGET __attribute__((always_inline)) inline
/// Four lanes of p spread over the rows of 8 lane pairs: lane k of the result holds p[rows[k]].
CCDLAB_AVX2_INLINE __m256i spread(const Index* p, __m256i rows) {
  return _mm256_permutevar8x32_epi32(_mm256_castsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))), rows);
}
/// Four lanes of p repeated over the columns: lane k holds p[k % 4].
CCDLAB_AVX2_INLINE __m256i repeat(const Index* p) {
  return _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
/// The sign bits of eight 32-bit lanes.
CCDLAB_AVX2_INLINE unsigned signs(__m256i v) { return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(v))); }
/// v's lanes packed by a row of a compress table (detail::CompressTable), stored whole at `out`.
CCDLAB_AVX2_INLINE void store_packed(void* out, __m256i v, const std::array<std::int32_t, 8>& pick) {
  _mm256_storeu_si256(static_cast<__m256i*>(out),
                      _mm256_permutevar8x32_epi32(v, _mm256_load_si256(reinterpret_cast<const __m256i*>(pick.data()))));
}
#undef CCDLAB_AVX2_INLINE

/// The AVX2 pair visit: what the AVX-512 one does, in two 8-lane halves (rows 0–1 and 2–3), the compress-stores
/// as one lane permutation from a table per 8-bit (or, for the 64-bit candidates, 4-bit) mask and a full store.
/// Same candidates and pushes, in the same order.
template <class BV>
CCDLAB_AVX2_TARGET __attribute__((always_inline)) inline LanePairAnswer visit_lane_pairs(
    const WideBounds<BV>& A, const WideBounds<BV>& B, Index ra, Index rb, unsigned allowed, bool self,
    LanePairCursor& cur) {
  constexpr int W = WideLayout::kWidth;
  const __m256i rows[2] = {_mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1), _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3)};
  const __m256i cols = _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3);
  unsigned all = overlapping_lane_pairs_avx2(A, B);
  if (cur.ends_a) all &= ~lane_pairs_apart_at_both_ends_avx2(cur.ends_a[ra], cur.ends_b[rb]);
  const unsigned hit = all & allowed;
  const __m256i sa[2] = {spread(A.lanes.slot.data(), rows[0]), spread(A.lanes.slot.data(), rows[1])};
  const __m256i sb = repeat(B.lanes.slot.data());
  const unsigned leaves = (signs(sa[0]) | signs(sa[1]) << 8) & (signs(sb) * 0x101u);
  unsigned emit = hit & leaves;
  const unsigned down = hit & ~leaves;
  unsigned adjacent = 0;
  if (emit) {
    const __m256i ones = _mm256_set1_epi32(-1);
    const __m256i fb = _mm256_xor_si256(sb, ones);  // ~slot = face
    __m256i first[2] = {_mm256_xor_si256(sa[0], ones), _mm256_xor_si256(sa[1], ones)}, second[2] = {fb, fb};
    if (self) {  // TriMesh::faces_adjacent on 16 lane pairs; candidates ordered (min, max)
      unsigned shared = 0;
      for (int p = 0; p < 3; ++p)
        for (int h = 0; h < 2; ++h) {
          const __m256i va = spread(A.lanes.vert[p].data(), rows[h]);
          for (int q = 0; q < 3; ++q)
            shared |= signs(_mm256_cmpeq_epi32(va, repeat(B.lanes.vert[q].data()))) << (8 * h);
        }
      adjacent = emit & shared;
      emit &= ~shared;
      for (int h = 0; h < 2; ++h) {
        const __m256i lo = _mm256_min_epi32(first[h], second[h]), hi = _mm256_max_epi32(first[h], second[h]);
        first[h] = lo, second[h] = hi;
      }
    }
    for (int g = 0; g < 4; ++g) {  // four lane pairs at a time, as 64-bit (first, second) = FacePair
      const __m128i f = g % 2 ? _mm256_extracti128_si256(first[g / 2], 1) : _mm256_castsi256_si128(first[g / 2]);
      const __m128i s = g % 2 ? _mm256_extracti128_si256(second[g / 2], 1) : _mm256_castsi256_si128(second[g / 2]);
      const __m256i pair = _mm256_or_si256(_mm256_cvtepu32_epi64(f), _mm256_slli_epi64(_mm256_cvtepu32_epi64(s), 32));
      const unsigned m = (emit >> (4 * g)) & 0xFu;
      store_packed(cur.pout, pair, detail::kCompress64x4.lanes[m]);
      cur.pout += std::popcount(m);
    }
  }
  if (down) {
    const __m256i hb = _mm256_add_epi32(_mm256_set1_epi32(rb * W), cols);
    for (int h = 0; h < 2; ++h) {
      const unsigned m = (down >> (8 * h)) & 0xFFu;
      const auto& pick = detail::kCompress32x8.lanes[m];
      const __m256i ha = _mm256_add_epi32(_mm256_set1_epi32(ra * W), rows[h]);
      store_packed(cur.col_ha + cur.top, ha, pick), store_packed(cur.col_hb + cur.top, hb, pick);
      store_packed(cur.col_wa + cur.top, sa[h], pick), store_packed(cur.col_wb + cur.top, sb, pick);
      cur.top += std::size_t(std::popcount(m));
    }
  }
  return {all, hit, down, adjacent};
}

#define CCDLAB_WALK_TARGET CCDLAB_AVX2_TARGET
#include "framework/traversal/lane_pair_walk-inl.hpp"
#undef CCDLAB_WALK_TARGET
}  // namespace lane_pair_avx2

#endif  // CCDLAB_HAS_LANE_PAIR_WALKS

}  // namespace ccdlab
