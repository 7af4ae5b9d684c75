#pragma once
// Overlap tests of the 4-wide view's lanes (framework/hierarchy/wide_bvh.hpp).
//   overlapping_lanes      — one k-DOP against the four lanes of a record: one 4-float compare per axis and side.
//                            Four floats are exactly one SSE2 register, and SSE2 is part of every x86-64 CPU, so
//                            this needs no run-time dispatch and stays inline in the traversal loop (Highway's
//                            static target on a baseline x86-64 build is its scalar one, one lane).
//   overlapping_lane_pairs — the 4 × 4 lane pairs of two records: one 16-float compare per axis and side, in
//                            AVX-512 (16 floats are one register); overlapping_lane_pairs_avx2 the same in two
//                            8-float halves. Compiled for their instruction sets by function attributes and called
//                            only where the CPU has them (lane_pair_walk), so the default build still runs on any
//                            x86-64 CPU.
// The plain loops are the reference the tests compare with, and what other CPUs take.
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// GCC 12's AVX-512 headers make their "undefined" vectors by self-initialisation (`__m512 __Y = __Y;`), which
// -Wmaybe-uninitialized reports once a kernel inlines them (GCC bug 105593, fixed in GCC 13): a false positive,
// silenced for the lines of those headers only. This must be the translation unit's first <immintrin.h>.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#else
#include <immintrin.h>
#endif
/// What the AVX-512 code is compiled for: Highway's AVX3 target (AVX-512 F/VL/DQ/BW and the AVX2 set below it).
#define CCDLAB_AVX512_TARGET \
  __attribute__((target("avx2,bmi,bmi2,lzcnt,popcnt,avx512f,avx512vl,avx512dq,avx512bw")))
/// What the AVX2 code is compiled for: Highway's AVX2 target.
#define CCDLAB_AVX2_TARGET __attribute__((target("avx2,bmi,bmi2,lzcnt,popcnt,fma,f16c")))
/// The lane-pair walks (AVX-512 and AVX2) compile here.
#define CCDLAB_HAS_LANE_PAIR_WALKS 1
#endif

#include "framework/hierarchy/wide_bvh.hpp"

namespace ccdlab {

/// Bit j set ⇔ lane j's k-DOP overlaps q (closed intervals on every axis, as KDop::overlaps). Empty lanes never do.
/// q: a BV or a WideLane<BV> (anything with min(i), max(i)).
template <class BV, class Query>
inline unsigned overlapping_lanes_plain(const WideBounds<BV>& w, const Query& q) {
  unsigned mask = 0;
  for (int j = 0; j < WideLayout::kWidth; ++j) {
    unsigned apart = 0;  // every axis tested, no branch: `|` on 0/1 values, not `||`
    for (int i = 0; i < BV::num_axes; ++i) apart |= unsigned(w.lo[i][j] > q.max(i)) | unsigned(q.min(i) > w.hi[i][j]);
    mask |= unsigned(apart == 0) << j;
  }
  return mask;
}

/// Bit 4i + j set ⇔ lane i of a overlaps lane j of b (closed intervals, as KDop::overlaps). Empty lanes never do.
template <class BV>
inline unsigned overlapping_lane_pairs_plain(const WideBounds<BV>& a, const WideBounds<BV>& b) {
  unsigned mask = 0;
  for (int i = 0; i < WideLayout::kWidth; ++i)
    mask |= overlapping_lanes_plain(b, WideLane<BV>{&a, i}) << (4 * i);
  return mask;
}

/// Bit j set ⇔ lane j of w and lane k of q are apart at both ends of the step on one of x, y, z, on the same
/// side (apart_at_both_ends, end_boxes.hpp, on WideEnds lanes).
inline unsigned lanes_apart_at_both_ends_plain(const WideEnds& w, const WideEnds& q, int k) {
  unsigned mask = 0;
  for (int j = 0; j < WideLayout::kWidth; ++j) {
    bool apart = false;
    for (int c = 0; c < 3; ++c) {
      apart |= (w.hi[0][c][j] < q.lo[0][c][k]) & (w.hi[1][c][j] < q.lo[1][c][k]);
      apart |= (q.hi[0][c][k] < w.lo[0][c][j]) & (q.hi[1][c][k] < w.lo[1][c][j]);
    }
    mask |= unsigned(apart) << j;
  }
  return mask;
}

/// Bit 4i + j set ⇔ lane i of a and lane j of b are apart at both ends of the step.
inline unsigned lane_pairs_apart_at_both_ends_plain(const WideEnds& a, const WideEnds& b) {
  unsigned mask = 0;
  for (int i = 0; i < WideLayout::kWidth; ++i) mask |= lanes_apart_at_both_ends_plain(b, a, i) << (4 * i);
  return mask;
}

/// Which lane-pair walk traverse_bvtt and the wide front take: the best of AVX-512 and AVX2 that this CPU has and
/// CCDLAB_SIMD (Highway's supported targets) allows, or none (the SSE2 walk, traverse_bvtt_wide, and the binary
/// front). Cheap (Highway's chosen target, no CPUID): asked once per traversal call.
enum class LanePairWalk : std::uint8_t { none, avx2, avx512 };
LanePairWalk lane_pair_walk();

/// The lanes' size measures (KDop::size_measure: the extents along the first three axes, summed in that order).
template <class BV>
inline void lane_sizes_plain(const WideBounds<BV>& w, float* out) {
  for (int j = 0; j < WideLayout::kWidth; ++j)
    out[j] = (w.hi[0][j] - w.lo[0][j]) + (w.hi[1][j] - w.lo[1][j]) + (w.hi[2][j] - w.lo[2][j]);
}

#if defined(__SSE2__)
static_assert(WideLayout::kWidth == 4, "one SSE2 register per axis and side");

template <class BV, class Query>
inline unsigned overlapping_lanes(const WideBounds<BV>& w, const Query& q) {
  __m128 apart = _mm_setzero_ps();
  for (int i = 0; i < BV::num_axes; ++i) {
    apart = _mm_or_ps(apart, _mm_cmpgt_ps(_mm_load_ps(w.lo[i]), _mm_set1_ps(q.max(i))));
    apart = _mm_or_ps(apart, _mm_cmpgt_ps(_mm_set1_ps(q.min(i)), _mm_load_ps(w.hi[i])));
  }
  return ~unsigned(_mm_movemask_ps(apart)) & 0xFu;
}

inline unsigned lanes_apart_at_both_ends(const WideEnds& w, const WideEnds& q, int k) {
  __m128 apart = _mm_setzero_ps();
  for (int c = 0; c < 3; ++c) {
    const auto below = [&](int f) { return _mm_cmplt_ps(_mm_load_ps(w.hi[f][c]), _mm_set1_ps(q.lo[f][c][k])); };
    const auto above = [&](int f) { return _mm_cmplt_ps(_mm_set1_ps(q.hi[f][c][k]), _mm_load_ps(w.lo[f][c])); };
    apart = _mm_or_ps(apart, _mm_or_ps(_mm_and_ps(below(0), below(1)), _mm_and_ps(above(0), above(1))));
  }
  return unsigned(_mm_movemask_ps(apart));
}

template <class BV>
inline void lane_sizes(const WideBounds<BV>& w, float* out) {
  const auto extent = [&](int i) { return _mm_sub_ps(_mm_load_ps(w.hi[i]), _mm_load_ps(w.lo[i])); };
  _mm_storeu_ps(out, _mm_add_ps(_mm_add_ps(extent(0), extent(1)), extent(2)));
}
#endif

#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
/// Lane i of a, repeated four times, for i = 0..3: the rows of the 4 × 4 lane pairs (lane 4i + j holds a's i).
#define CCDLAB_LANE_ROWS _mm512_set_epi32(3, 3, 3, 3, 2, 2, 2, 2, 1, 1, 1, 1, 0, 0, 0, 0)

/// overlapping_lane_pairs_plain in AVX-512: per axis, a's lanes spread over the rows (one permute), b's four
/// lanes repeated over the columns (one broadcast load), two compares into a mask register.
template <class BV>
CCDLAB_AVX512_TARGET __attribute__((always_inline)) inline unsigned overlapping_lane_pairs(const WideBounds<BV>& a,
                                                                                           const WideBounds<BV>& b) {
  const __m512i rows = CCDLAB_LANE_ROWS;
  __mmask16 apart = 0;
  for (int i = 0; i < BV::num_axes; ++i) {
    const __m512 alo = _mm512_permutexvar_ps(rows, _mm512_castps128_ps512(_mm_load_ps(a.lo[i])));
    const __m512 ahi = _mm512_permutexvar_ps(rows, _mm512_castps128_ps512(_mm_load_ps(a.hi[i])));
    const __m512 blo = _mm512_broadcast_f32x4(_mm_load_ps(b.lo[i]));
    const __m512 bhi = _mm512_broadcast_f32x4(_mm_load_ps(b.hi[i]));
    apart |= _mm512_cmp_ps_mask(alo, bhi, _CMP_GT_OQ) | _mm512_cmp_ps_mask(blo, ahi, _CMP_GT_OQ);
  }
  return unsigned(~apart) & 0xFFFFu;
}

/// lane_pairs_apart_at_both_ends_plain in AVX-512: per axis and side, the two ends' compares of the 16 lane pairs.
CCDLAB_AVX512_TARGET __attribute__((always_inline)) inline unsigned lane_pairs_apart_at_both_ends(const WideEnds& a,
                                                                                                 const WideEnds& b) {
  const __m512i rows = CCDLAB_LANE_ROWS;
#define row(p) _mm512_permutexvar_ps(rows, _mm512_castps128_ps512(_mm_load_ps(p)))
#define col(p) _mm512_broadcast_f32x4(_mm_load_ps(p))
  __mmask16 apart = 0;
  for (int c = 0; c < 3; ++c) {
    apart |= _mm512_cmp_ps_mask(row(a.hi[0][c]), col(b.lo[0][c]), _CMP_LT_OQ) & _mm512_cmp_ps_mask(row(a.hi[1][c]), col(b.lo[1][c]), _CMP_LT_OQ);
    apart |= _mm512_cmp_ps_mask(col(b.hi[0][c]), row(a.lo[0][c]), _CMP_LT_OQ) & _mm512_cmp_ps_mask(col(b.hi[1][c]), row(a.lo[1][c]), _CMP_LT_OQ);
  }
#undef row
#undef col
  return unsigned(apart);
}

/// overlapping_lane_pairs in AVX2: the same 16 lanes as two 8-float halves (rows 0–1 and 2–3), same answer.
template <class BV>
CCDLAB_AVX2_TARGET __attribute__((always_inline)) inline unsigned overlapping_lane_pairs_avx2(const WideBounds<BV>& a,
                                                                                              const WideBounds<BV>& b) {
  const __m256i rows01 = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1), rows23 = _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3);
  __m256 apart01 = _mm256_setzero_ps(), apart23 = _mm256_setzero_ps();
  for (int i = 0; i < BV::num_axes; ++i) {
    const __m256 alo = _mm256_castps128_ps256(_mm_load_ps(a.lo[i])), ahi = _mm256_castps128_ps256(_mm_load_ps(a.hi[i]));
    const __m256 blo = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(b.lo[i]));
    const __m256 bhi = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(b.hi[i]));
    // (No lambda: GCC does not give a lambda its enclosing function's target.)
    apart01 = _mm256_or_ps(apart01, _mm256_or_ps(_mm256_cmp_ps(_mm256_permutevar8x32_ps(alo, rows01), bhi, _CMP_GT_OQ),
                                                 _mm256_cmp_ps(blo, _mm256_permutevar8x32_ps(ahi, rows01), _CMP_GT_OQ)));
    apart23 = _mm256_or_ps(apart23, _mm256_or_ps(_mm256_cmp_ps(_mm256_permutevar8x32_ps(alo, rows23), bhi, _CMP_GT_OQ),
                                                 _mm256_cmp_ps(blo, _mm256_permutevar8x32_ps(ahi, rows23), _CMP_GT_OQ)));
  }
  const unsigned apart = unsigned(_mm256_movemask_ps(apart01)) | unsigned(_mm256_movemask_ps(apart23)) << 8;
  return ~apart & 0xFFFFu;
}

/// lane_pairs_apart_at_both_ends in AVX2: the same 16 lanes as two 8-float halves, same answer.
CCDLAB_AVX2_TARGET __attribute__((always_inline)) inline unsigned lane_pairs_apart_at_both_ends_avx2(const WideEnds& a,
                                                                                                    const WideEnds& b) {
  const __m256i rows[2] = {_mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1), _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3)};
#define CCDLAB_ROW(p, h) _mm256_permutevar8x32_ps(_mm256_castps128_ps256(_mm_load_ps(p)), rows[h])
#define CCDLAB_COL(p) _mm256_broadcast_ps(reinterpret_cast<const __m128*>(p))
  unsigned apart = 0;
  for (int h = 0; h < 2; ++h) {
    __m256 m = _mm256_setzero_ps();
    for (int c = 0; c < 3; ++c) {
      m = _mm256_or_ps(m, _mm256_and_ps(_mm256_cmp_ps(CCDLAB_ROW(a.hi[0][c], h), CCDLAB_COL(b.lo[0][c]), _CMP_LT_OQ),
                                        _mm256_cmp_ps(CCDLAB_ROW(a.hi[1][c], h), CCDLAB_COL(b.lo[1][c]), _CMP_LT_OQ)));
      m = _mm256_or_ps(m, _mm256_and_ps(_mm256_cmp_ps(CCDLAB_COL(b.hi[0][c]), CCDLAB_ROW(a.lo[0][c], h), _CMP_LT_OQ),
                                        _mm256_cmp_ps(CCDLAB_COL(b.hi[1][c]), CCDLAB_ROW(a.lo[1][c], h), _CMP_LT_OQ)));
    }
    apart |= unsigned(_mm256_movemask_ps(m)) << (8 * h);
  }
#undef CCDLAB_ROW
#undef CCDLAB_COL
  return apart;
}
#endif

#if !defined(__SSE2__)
inline unsigned lanes_apart_at_both_ends(const WideEnds& w, const WideEnds& q, int k) {
  return lanes_apart_at_both_ends_plain(w, q, k);
}
template <class BV, class Query>
inline unsigned overlapping_lanes(const WideBounds<BV>& w, const Query& q) {
  return overlapping_lanes_plain(w, q);
}
template <class BV>
inline void lane_sizes(const WideBounds<BV>& w, float* out) {
  lane_sizes_plain(w, out);
}
#endif

}  // namespace ccdlab
