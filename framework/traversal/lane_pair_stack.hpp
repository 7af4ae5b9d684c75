#pragma once
// The lane-pair walks' stack (four columns, one compress-store each per visit) and what one visit reads and
// writes: the lane pairs a stack entry tests, its records asked for ahead, the cursor into the stack and the
// candidates.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "framework/traversal/bvtt_view.hpp"
#include "framework/traversal/wide_overlap.hpp"
#include "framework/traversal/wide_walk.hpp"

namespace ccdlab {

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
#endif  // CCDLAB_HAS_LANE_PAIR_WALKS

}  // namespace ccdlab
