#pragma once
// The lane-pair walk in AVX-512: its pair visit (visit_lane_pairs) and, from lane_pair_walk-inl.hpp, the walk
// that calls it, compiled with the AVX-512 function attribute.
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
namespace lane_pair_avx512 {
/// One pair visit of the lane-pair walk — THE kernel every scheduler's BVTT work goes through at width 4 (the
/// walk below, the wide front in front/wide_front.hpp), in AVX-512: the `allowed` lane pairs of records A (index ra) and B
/// (rb) tested at once (overlapping_lane_pairs); overlapping leaf pairs written as candidates (adjacent ones
/// dropped in self passes, the pair ordered (min, max)), the other overlapping lane pairs pushed as children with
/// homes ra · 4 + i and rb · 4 + j (for a side restricted to one leaf lane, that is its home: it stays). No
/// branch on any answer: compress-stores.
template <class BV>
CCDLAB_AVX512_TARGET __attribute__((always_inline)) inline LanePairAnswer visit_lane_pairs(
    const WideBounds<BV>& A, const WideBounds<BV>& B, Index ra, Index rb, unsigned allowed, bool self,
    LanePairCursor& cur) {
  constexpr int W = WideLayout::kWidth;
  const __m512i rows = CCDLAB_LANE_ROWS;  // lane 4i + j: row i (a's lane), column j (b's lane)
  const __m512i cols = _mm512_set_epi32(3, 2, 1, 0, 3, 2, 1, 0, 3, 2, 1, 0, 3, 2, 1, 0);
  const auto load4 = [](const Index* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); };
  unsigned all = overlapping_lane_pairs(A, B);
  if (cur.ends_a) all &= ~lane_pairs_apart_at_both_ends(cur.ends_a[ra], cur.ends_b[rb]);
  const unsigned hit = all & allowed;
  // Each lane pair's slots; a slot < 0 is a leaf (~face).
  const __m512i sa = _mm512_permutexvar_epi32(rows, _mm512_castsi128_si512(load4(A.lanes.slot.data())));
  const __m512i sb = _mm512_broadcast_i32x4(load4(B.lanes.slot.data()));
  const unsigned leaves = _mm512_movepi32_mask(sa) & _mm512_movepi32_mask(sb);
  unsigned emit = hit & leaves;
  const unsigned down = hit & ~leaves;
  unsigned adjacent = 0;
  if (emit) {
    const __m512i ones = _mm512_set1_epi32(-1);
    const __m512i fa = _mm512_xor_si512(sa, ones), fb = _mm512_xor_si512(sb, ones);  // ~slot = face
    __m512i first = fa, second = fb;
    if (self) {  // TriMesh::faces_adjacent on 16 lane pairs; candidates ordered (min, max)
      __mmask16 shared = 0;
      for (int p = 0; p < 3; ++p) {
        const __m512i va = _mm512_permutexvar_epi32(rows, _mm512_castsi128_si512(load4(A.lanes.vert[p].data())));
        for (int q = 0; q < 3; ++q)
          shared |= _mm512_cmpeq_epi32_mask(va, _mm512_broadcast_i32x4(load4(B.lanes.vert[q].data())));
      }
      adjacent = emit & unsigned(shared);
      emit &= ~unsigned(shared);
      first = _mm512_min_epi32(fa, fb), second = _mm512_max_epi32(fa, fb);
    }
    // Interleave (lo, hi) of lanes 0..7 and 8..15 into FacePairs.
    const __m512i pairs_0_7 = _mm512_set_epi32(23, 7, 22, 6, 21, 5, 20, 4, 19, 3, 18, 2, 17, 1, 16, 0);
    const __m512i pairs_8_15 = _mm512_set_epi32(31, 15, 30, 14, 29, 13, 28, 12, 27, 11, 26, 10, 25, 9, 24, 8);
    const __m512i p0 = _mm512_permutex2var_epi32(first, pairs_0_7, second);
    const __m512i p1 = _mm512_permutex2var_epi32(first, pairs_8_15, second);
    _mm512_storeu_si512(cur.pout, _mm512_maskz_compress_epi64(__mmask8(emit), p0));
    cur.pout += std::popcount(emit & 0xFFu);
    _mm512_storeu_si512(cur.pout, _mm512_maskz_compress_epi64(__mmask8(emit >> 8), p1));
    cur.pout += std::popcount(emit >> 8);
  }
  if (down) {
    // The children's homes: record · 4 + lane (a leaf side restricted to its home lane keeps its home); their
    // slots are the lanes' (sa / sb).
    const __m512i ha16 = _mm512_add_epi32(_mm512_set1_epi32(ra * W), rows);
    const __m512i hb16 = _mm512_add_epi32(_mm512_set1_epi32(rb * W), cols);
    const __mmask16 m = __mmask16(down);
    _mm512_storeu_si512(cur.col_ha + cur.top, _mm512_maskz_compress_epi32(m, ha16));
    _mm512_storeu_si512(cur.col_hb + cur.top, _mm512_maskz_compress_epi32(m, hb16));
    _mm512_storeu_si512(cur.col_wa + cur.top, _mm512_maskz_compress_epi32(m, sa));
    _mm512_storeu_si512(cur.col_wb + cur.top, _mm512_maskz_compress_epi32(m, sb));
    cur.top += std::size_t(std::popcount(down));
  }
  return {all, hit, down, adjacent};
}

#define CCDLAB_WALK_TARGET CCDLAB_AVX512_TARGET
#include "framework/traversal/lane_pair_walk-inl.hpp"
#undef CCDLAB_WALK_TARGET
}  // namespace lane_pair_avx512

#endif  // CCDLAB_HAS_LANE_PAIR_WALKS

}  // namespace ccdlab
