#pragma once
// The walks over the 4-wide view (bv.width: 4; framework/hierarchy/wide_bvh.hpp, docs/wide-bvh.md). Both make
// the binary BVTT's candidates (see wide_bvh.hpp for why skipping levels keeps them):
//   traverse_bvtt_lane_pairs — AVX-512 or AVX2: a pair node opens both sides' records and tests their 4 × 4 lane
//                              pairs in one 16-lane compare per axis (two 8-lane ones in AVX2); no branch on the
//                              answers (compress-stores; table permutations in AVX2).
//   traverse_bvtt_wide       — any x86-64 (SSE2): a pair node opens its larger side's record and tests its four
//                              lanes against the other side; the walk for CPUs without AVX2.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "framework/traversal/bvtt_view.hpp"
#include "framework/traversal/wide_overlap.hpp"

namespace ccdlab {

/// A node on the wide traversal's stack, carrying what its visit needs so that it reads no binary node. A pair
/// node (known to overlap): each side's home (WideLayout::home: the lane that holds its k-DOP, record · 4 + lane),
/// wide slot (a wide node, or ~face for a leaf) and size measure. A self node (self passes only): ha == hb ==
/// the node's id (a pair node's sides are different lanes, so its homes differ).
struct WideBvttEntry {
  Index ha, hb;
  Index wa, wb;
  float sa, sb;
  [[nodiscard]] bool both_leaves() const { return (wa & wb) < 0; }  // slots ~face
  /// The descent rule (bvtt_rule::descend_a) on the entry: open a's record (true) or b's.
  [[nodiscard]] bool descends_a() const { return bvtt_rule::descend_a(wa < 0, wb < 0, sa, sb); }
};

/// The 16-bit lane-pair mask (bit 4i + j: a's lane i, b's lane j) of the rows in `lanes` (bit i: a's lane i).
constexpr unsigned lane_rows_mask(unsigned lanes) {
  return (lanes & 1u) * 0xFu | (lanes >> 1 & 1u) * 0xF0u | (lanes >> 2 & 1u) * 0xF00u | (lanes >> 3 & 1u) * 0xF000u;
}

/// Lanes of a record that hold a node (BV tests when it is opened): 2, 3 or 4, the empty ones last.
template <class BV>
int used_lanes(const WideBounds<BV>& r) {
  constexpr int W = WideLayout::kWidth;
  return W - (r.lanes.slot[W - 1] == WideLayout::kNoSlot) - (r.lanes.slot[W - 2] == WideLayout::kNoSlot);
}

/// Depth-first traversal over the 4-wide view: a pair node's larger side opens all its lanes at once and only
/// the lanes that overlap the other side are pushed (test before push). Self nodes still open into (L, L),
/// (R, R), (L, R) as in the binary BVTT, so normal-cone skips apply unchanged. The descent rule is the binary
/// one (the larger side by size_measure, never a leaf); the candidates are the same (see wide_bvh.hpp).
/// Written like the binary walk (raw pointers, candidates written in place). A pair visit reads the record it
/// opens and the other side's k-DOP from the lane that holds it, in a record opened a moment ago: reading it
/// from the binary array instead misses the cache. A hit lane whose own
/// visit would open the other side's record (the usual case: a lane is two levels smaller) is not pushed: that
/// test is made at once, while both records are in cache. Same BV tests as pushing it, in another order.
template <class BV>
void traverse_bvtt_wide(const BvttView<BV>& v, BvttNode start, std::vector<WideBvttEntry>& stack, FacePairs& pairs,
                        std::uint64_t& bv_tests_out) {
  constexpr int W = WideLayout::kWidth;
  const BvhNode* const na = v.side_a.bvh->nodes.data();
  const BV* const bva = v.side_a.bv->data();
  const BV* const bvb = v.side_b.bv->data();
  const WideSideArrays<BV> side_a(v.side_a), side_b(v.side_b);  // end boxes on: both sides' ends, else neither
  const bool self = v.self;
  std::uint64_t bv_tests = 0;
  const auto pair_entry = [&](Index a, Index b) {
    return WideBvttEntry{side_a.home[a], side_b.home[b], side_a.slot[a], side_b.slot[b], bva[a].size_measure(), bvb[b].size_measure()};
  };
  // A visit pushes at most W · W pair nodes, or 2 entries for a self node; room is checked before each visit.
  if (stack.size() < 64) stack.resize(64);
  WideBvttEntry* base = stack.data();
  WideBvttEntry* top = base;
  WideBvttEntry* room = base + stack.size() - W * W;
  std::size_t emitted = pairs.size();
  pairs.resize(std::max<std::size_t>(pairs.capacity(), emitted + 1024));
  FacePair* pout = pairs.data() + emitted;
  FacePair* pend = pairs.data() + pairs.size();
  WideBvttEntry n{start.a, start.b, -1, -1, 0, 0};
  bool visit = true;
  if (!(self && start.a == start.b)) {
    ++bv_tests;
    visit = v.nodes_overlap(start.a, start.b);
    if (visit) n = pair_entry(start.a, start.b);
  }
  const auto emit = [&](const WideBvttEntry& leaves) {  // the candidate of two overlapping leaves
    if (pout == pend) [[unlikely]] {
      emitted = std::size_t(pout - pairs.data());
      pairs.resize(2 * pairs.size());
      pout = pairs.data() + emitted;
      pend = pairs.data() + pairs.size();
    }
    pout = v.write_face_pair(pout, ~leaves.wa, ~leaves.wb);
  };
  alignas(16) float size[W];
  for (;;) {
    if (visit) {
      if (top > room) [[unlikely]] {
        const std::size_t used = std::size_t(top - base);
        stack.resize(2 * stack.size());
        base = stack.data();
        top = base + used;
        room = base + stack.size() - W * W;
      }
      if (self && n.ha == n.hb) {
        if (const BvhNode& A = na[n.ha]; v.self_opens(A, n.ha)) {
          const auto c = BvttView<BV>::self_children(A);  // (L, L) next, (R, R) stacked, (L, R) tested first
          ++bv_tests;
          if (v.nodes_overlap(c.node[2].a, c.node[2].b)) *top++ = pair_entry(c.node[2].a, c.node[2].b);
          *top++ = {c.node[1].a, c.node[1].b, -1, -1, 0, 0};
          n = {c.node[0].a, c.node[0].b, -1, -1, 0, 0};
          continue;
        }
      } else if (n.both_leaves()) {
        emit(n);
      } else {
        const bool down_a = n.descends_a();
        const auto side_of = [&](bool a_side) { return a_side ? side_a.records : side_b.records; };
        const auto ends_of = [&](bool a_side) { return a_side ? side_a.ends : side_b.ends; };
        const Index rx = down_a ? n.wa : n.wb;  // the record opened
        const WideBounds<BV>& bx = side_of(down_a)[rx];
        const Index h = down_a ? n.hb : n.ha;  // the other side's home
        unsigned hit = overlapping_lanes(bx, WideLane<BV>{side_of(!down_a) + h / W, h % W});
        if (side_a.ends) hit &= ~lanes_apart_at_both_ends(ends_of(down_a)[rx], ends_of(!down_a)[h / W], h % W);
        bv_tests += used_lanes(bx);
        if (hit) {
          lane_sizes(bx, size);
          const Index ry = down_a ? n.wb : n.wa;  // the other side's record, if it is inner
          alignas(16) float size_y[W];
          bool sized_y = false;
          const auto lane_child = [](WideBvttEntry c, bool a_side, Index record, const WideBounds<BV>& b,
                                     const float* sz, int j) {
            if (a_side) {
              c.ha = record * W + j, c.wa = b.lanes.slot[j], c.sa = sz[j];
            } else {
              c.hb = record * W + j, c.wb = b.lanes.slot[j], c.sb = sz[j];
            }
            return c;
          };
          // A pair node found to overlap: emitted if both are leaves, else pushed, its next record asked for.
          const auto settle = [&](const WideBvttEntry& c) {
            if (c.both_leaves()) {
              emit(c);
              return;
            }
            const char* r = reinterpret_cast<const char*>(c.descends_a() ? side_a.records + c.wa : side_b.records + c.wb);
            for (std::size_t line = 0; line < sizeof(WideBounds<BV>); line += 64) __builtin_prefetch(r + line);
            *top++ = c;
          };
          for (; hit; hit &= hit - 1) {
            const int j = std::countr_zero(hit);
            const WideBvttEntry c = lane_child(n, down_a, rx, bx, size, j);
            // The visit of c would open the other side's record with lane j as its query (the binary rule):
            // make that test now, while both records are in cache, instead of pushing c.
            if (c.both_leaves() || c.descends_a() == down_a) {
              settle(c);
              continue;
            }
            const WideBounds<BV>& by = side_of(!down_a)[ry];
            unsigned hit_y = overlapping_lanes(by, WideLane<BV>{&bx, j});
            if (side_a.ends) hit_y &= ~lanes_apart_at_both_ends(ends_of(!down_a)[ry], ends_of(down_a)[rx], j);
            bv_tests += used_lanes(by);
            if (hit_y && !sized_y) lane_sizes(by, size_y), sized_y = true;
            for (; hit_y; hit_y &= hit_y - 1) settle(lane_child(c, !down_a, ry, by, size_y, std::countr_zero(hit_y)));
          }
        }
      }
    }
    if (top == base) break;
    n = *--top;
    visit = true;
  }
  pairs.resize(std::size_t(pout - pairs.data()));
  bv_tests_out += bv_tests;
}


/// The lane-pair walk's stack: four columns (each side's home and slot, as WideBvttEntry without the sizes), so
/// that a visit pushes all its overlapping lane pairs with one compress-store per column. A self node is (id, id,
/// −1, −1). Each column has room for 16 more entries than `cap` holds, for the full-width stores.
class LanePairStack {
 public:
  static constexpr std::size_t kSlack = 16;
  std::size_t cap() const { return cap_; }
  Index* column(int c) { return buf_.data() + std::size_t(c) * (cap_ + kSlack); }
  /// Room for at least `n` entries, keeping the first `used`.
  void reserve(std::size_t n, std::size_t used) {
    if (n <= cap_) return;
    std::size_t cap = std::max<std::size_t>(256, cap_);
    while (cap < n) cap *= 2;
    std::vector<Index> grown(4 * (cap + kSlack));
    if (used > 0)  // (an empty buffer's data() is null: no column to copy, nor to point into)
      for (int c = 0; c < 4; ++c) std::copy_n(column(c), used, grown.data() + std::size_t(c) * (cap + kSlack));
    buf_.swap(grown);
    cap_ = cap;
  }

 private:
  std::vector<Index> buf_;
  std::size_t cap_ = 0;
};

#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
/// The lane-pair walk's stack columns and candidate cursor, as one visit writes them.
struct LanePairCursor {
  Index* col_ha;
  Index* col_hb;
  Index* col_wa;
  Index* col_wb;
  std::size_t top;  ///< entries on the stack
  FacePair* pout;   ///< where the next candidate goes (room for W · W more, checked by the caller)
  const WideEnds* ends_a;  ///< end boxes of the records' lanes (BvttSide::wide_ends), or nullptr
  const WideEnds* ends_b;
};

/// What one pair visit found among its `allowed` lane pairs (bit 4i + j: lane i of record a, lane j of record b).
struct LanePairAnswer {
  unsigned all;       ///< every overlapping lane pair of the two records, allowed or not
  unsigned hit;       ///< overlapping lane pairs (allowed)
  unsigned down;      ///< overlapping lane pairs with an inner side: pushed as children
  unsigned adjacent;  ///< overlapping leaf pairs of faces that share a vertex (self passes): never candidates
};

/// The lane pairs a visit of stack entry (ha, hb, wa, wb) tests: all used lanes of an inner side's record, a leaf
/// side's home lane only. Sets the records it opens.
template <class BV>
inline unsigned entry_lane_pairs(const WideBounds<BV>* wide_a, const WideBounds<BV>* wide_b, Index ha, Index hb,
                                 Index wa, Index wb, Index& ra, Index& rb) {
  constexpr int W = WideLayout::kWidth;
  ra = wa >= 0 ? wa : ha / W, rb = wb >= 0 ? wb : hb / W;
  const unsigned row_lanes = wa >= 0 ? (1u << used_lanes(wide_a[ra])) - 1 : 1u << (ha % W);
  const unsigned col_lanes = wb >= 0 ? (1u << used_lanes(wide_b[rb])) - 1 : 1u << (hb % W);
  return lane_rows_mask(row_lanes) & (col_lanes * 0x1111u);
}

/// Asks for the records that stack entry `i` will open (the walks prefetch the entry two below the top).
template <class BV>
inline void prefetch_entry_records(const WideBounds<BV>* wide_a, const WideBounds<BV>* wide_b, const LanePairCursor& c,
                                   std::size_t i) {
  constexpr int W = WideLayout::kWidth;
  const Index wa = c.col_wa[i], wb = c.col_wb[i];
  const Index a = wa >= 0 ? wa : c.col_ha[i] / W, b = wb >= 0 ? wb : c.col_hb[i] / W;
  const char* ra = reinterpret_cast<const char*>(wide_a + a);
  const char* rb = reinterpret_cast<const char*>(wide_b + b);
  for (std::size_t line = 0; line < sizeof(WideBounds<BV>); line += 64) __builtin_prefetch(ra + line), __builtin_prefetch(rb + line);
  if (c.ends_a) {
    const char* ea = reinterpret_cast<const char*>(c.ends_a + a);
    const char* eb = reinterpret_cast<const char*>(c.ends_b + b);
    for (std::size_t line = 0; line < sizeof(WideEnds); line += 64) __builtin_prefetch(ea + line), __builtin_prefetch(eb + line);
  }
}

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

// The lane-pair walk, compiled once per instruction set: each namespace has its visit_lane_pairs, and
// lane_pair_walk-inl.hpp the walk that calls it, built with that set's function attribute.
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

/// The lane-pair walk of `walk` (not none).
template <class BV>
void traverse_bvtt_lane_pairs(LanePairWalk walk, const BvttView<BV>& v, BvttNode start, LanePairStack& stack,
                              FacePairs& pairs, std::uint64_t& bv_tests) {
  if (walk == LanePairWalk::avx512) lane_pair_avx512::traverse_bvtt_lane_pairs(v, start, stack, pairs, bv_tests);
  else lane_pair_avx2::traverse_bvtt_lane_pairs(v, start, stack, pairs, bv_tests);
}
#endif

}  // namespace ccdlab
