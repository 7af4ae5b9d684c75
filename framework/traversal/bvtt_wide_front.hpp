#pragma once
// The BVTT front on the 4-wide view (bv.width: 4 where the CPU has the lane-pair walk): the seed paper's front
// (bvtt_front.hpp) walked by the same kernel as every other scheduler, visit_lane_pairs (bvtt_wide.hpp).
//
// What the front holds. A BVTT node is a pair (x, y) of binary BVH nodes; in the wide view every node sits in some
// record's lane (WideLayout::home), so a node pair is a LANE PAIR of two records. The front is a cut of the BVTT —
// node pairs covering disjoint sets of leaf pairs whose union is every non-adjacent leaf pair (self passes) or
// every leaf pair (two bodies) — stored as GROUPS: two records (ra, rb) and the 16-bit mask of their lane pairs
// that are on the cut (bit 4i + j: lane i of ra, lane j of rb). A group is what one visit of the lane-pair walk
// left behind: the lane pairs it tested and did not descend.
//
// One step, per group (in parallel chunks; each chunk writes the groups of the next front in its own piece):
//   KEEP    one visit_lane_pairs over the group's cut lane pairs: those that do not overlap stay; overlapping leaf
//           pairs are candidates and stay; adjacent leaf pairs (faces sharing a vertex: they always overlap and
//           never yield a candidate) leave the cut for good.
//   SPROUT  overlapping lane pairs with an inner side leave the cut: the walk runs below them, each of its visits
//           adding the group of what it did not descend. A lane pair's children are the lanes of its inner sides'
//           records (a leaf side stays itself): exactly its leaf pairs, so the cut stays a cut.
//   PRUNE   a carried-over group none of whose lane pairs overlaps, whose mask is every lane pair of a node pair's
//           visit (all used lanes of a record whose owner is x, or the one lane of a leaf x; likewise y; not two
//           single leaves, which is the node itself; in self passes x and y disjoint sub-trees), is replaced by
//           that node pair (x, y) — one more BV test — when (x, y) does not overlap either: its lane pair in the
//           records holding x and y, merged into the group just written when that is the same two records,
//           which may prune in turn. (x, y) covers exactly the group's leaf pairs, so the cut stays a cut.
//   REBUILD from seeds (wide_front_seeds), as the binary front does.
// Exactness: a leaf pair is a candidate iff its k-DOPs overlap. Every non-adjacent leaf pair lies below exactly
// one cut node; refit makes every node's k-DOP the union of its leaves', so an overlapping leaf pair's cut node
// overlaps, and so does every node the sprout walk visits on the way down to it: it is found, once. Nothing else
// is emitted. The candidates are therefore the sequential traversal's, whatever the chunks, threads or history.
// Normal cones: a cut lane pair inside a skipped patch (BvttView::in_skipped_patch) is kept untested this step,
// as the walk never opens the self node above it.
#include <cstdint>
#include <vector>

#include "framework/traversal/bvtt_front.hpp"
#include "framework/traversal/bvtt_wide.hpp"

namespace ccdlab {

struct WideFrontGroup {
  Index ra;  ///< record of side a
  Index rb;  ///< record of side b
  std::uint16_t cut;   ///< lane pairs on the cut: bit 4i + j, lane i of ra and lane j of rb
  std::uint8_t quiet;  ///< while a step writes it: carried over, and none of its lane pairs overlapped (may prune)
  std::uint8_t unused = 0;
};
static_assert(sizeof(WideFrontGroup) == 12, "a group is 3 words: keep the front compact");

/// The front a rebuild starts from, covering the BVTT below `root` (the whole BVTT, or one slice): (L, R) for
/// every inner node under a self node, the node itself otherwise, each split into the lane pairs of its visit
/// (without a BV test: they cover the same leaf pairs) until it covers at most 1/`granularity` of the pass's leaf
/// pairs (and no fewer than `min_pairs`), so that the first step's sprouts are spread over many tasks.
std::vector<WideFrontGroup> wide_front_seeds(const BvhTopology& a, const WideLayout& la, const BvhTopology& b,
                                             const WideLayout& lb, bool self, BvttNode root = {0, 0},
                                             double granularity = 512, double min_pairs = 4096);

/// The front's cut node pairs as binary node ids (flags 0), appended to `out`: for tests and `ccdlab export`.
void append_wide_front_nodes(const WideLayout& la, const WideLayout& lb, const std::vector<WideFrontGroup>& groups,
                             std::vector<FrontNode>& out);

#if defined(CCDLAB_HAS_AVX512_WALK)
/// Processes groups [begin, end) (AVX-512: call only where the view's lane_pairs is set): appends the next
/// front's groups to `next` and the candidates to `pairs`. `prune`: false at a rebuild (seeds are split for
/// balance, not to be merged back at once) or when the scheduler says so.
template <class BV>
CCDLAB_AVX512_TARGET void process_wide_front(const BvttView<BV>& v, const WideFrontGroup* begin,
                                             const WideFrontGroup* end, bool prune, std::vector<WideFrontGroup>& next,
                                             FacePairs& pairs, LanePairStack& stack, FrontCounters& counters) {
  constexpr int W = WideLayout::kWidth;
  const WideBounds<BV>* const wide_a = v.wide_a->data();
  const WideBounds<BV>* const wide_b = v.wide_b->data();
  const WideLayout& la = *v.wide_layout_a;
  const WideLayout& lb = *v.wide_layout_b;
  const BV* const bva = v.bv_a->data();
  const BV* const bvb = v.bv_b->data();
  const bool self = v.self;
  FrontCounters c;  // local: the caller's are written once, at the end
  LanePairCursor cur{nullptr, nullptr, nullptr, nullptr, 0, nullptr};
  const auto make_room = [&](std::size_t n) {
    stack.reserve(n, cur.top);
    cur.col_ha = stack.column(0), cur.col_hb = stack.column(1), cur.col_wa = stack.column(2), cur.col_wb = stack.column(3);
  };
  make_room(64);
  std::size_t emitted = pairs.size();
  pairs.resize(std::max<std::size_t>(pairs.capacity(), emitted + 1024));
  cur.pout = pairs.data() + emitted;
  FacePair* pend = pairs.data() + pairs.size();
  // Room for one visit: 16 more children on the stack, 16 more candidates.
  const auto room_for_visit = [&] {
    if (cur.top + W * W > stack.cap()) [[unlikely]] make_room(cur.top + W * W);
    if (cur.pout + W * W > pend) [[unlikely]] {
      emitted = std::size_t(cur.pout - pairs.data());
      pairs.resize(2 * pairs.size() + W * W);
      cur.pout = pairs.data() + emitted;
      pend = pairs.data() + pairs.size();
    }
  };
  // The node pair whose visit tests exactly g's lane pairs (see PRUNE above): its ids and homes, or false.
  const auto whole_visit_of = [&](const WideFrontGroup& g, Index& x, Index& y, Index& hx, Index& hy) {
    const unsigned cut = g.cut;
    unsigned rows = 0;
    for (int i = 0; i < W; ++i) rows |= unsigned((cut >> (W * i) & 0xFu) != 0) << i;
    const unsigned cols = (cut | cut >> 4 | cut >> 8 | cut >> 12) & 0xFu;
    if (cut != (lane_rows_mask(rows) & (cols * 0x1111u))) return false;
    const auto side = [&](const WideLayout& l, const WideBounds<BV>& rec, Index r, unsigned lanes, Index& n,
                          Index& h) {
      if (lanes == (1u << used_lanes(rec)) - 1) {  // every lane: the record's owner
        n = l.owner[std::size_t(r)];
        if (n < 0) return -1;  // the top record is nobody's
        h = l.home[std::size_t(n)];
        return 1;
      }
      const int j = std::countr_zero(lanes);
      if (std::popcount(lanes) != 1 || rec.lanes.slot[std::size_t(j)] >= 0) return -1;
      n = l.lanes[std::size_t(r)].node[std::size_t(j)], h = r * W + j;  // a leaf side stays itself
      return 0;
    };
    const int inner_a = side(la, wide_a[g.ra], g.ra, rows, x, hx);
    const int inner_b = side(lb, wide_b[g.rb], g.rb, cols, y, hy);
    if (inner_a < 0 || inner_b < 0 || inner_a + inner_b == 0) return false;
    if (self) {  // (x, y) must be a pair node: neither sub-tree holds the other
      const BvhTopology& t = *v.bvh_a;
      if ((y >= x && y < t.subtree_end(x)) || (x >= y && x < t.subtree_end(y))) return false;
    }
    return true;
  };
  // Appends a group, merged into the last one when it holds the same two records; then, while the last group is
  // quiet and is one node pair's whole visit, and that node pair does not overlap, prunes it into that node pair.
  const auto push_group = [&](Index ra, Index rb, unsigned cut, bool quiet) {
    if (!cut) return;
    if (!next.empty() && next.back().ra == ra && next.back().rb == rb) {
      next.back().cut = std::uint16_t(next.back().cut | cut);
      next.back().quiet &= std::uint8_t(quiet);
    } else {
      next.push_back(WideFrontGroup{ra, rb, std::uint16_t(cut), std::uint8_t(quiet)});
    }
    while (prune && next.back().quiet) {
      Index x, y, hx, hy;
      if (!whole_visit_of(next.back(), x, y, hx, hy)) break;
      ++c.bv_tests;
      if (bva[x].overlaps(bvb[y])) break;
      next.pop_back();
      ++c.pruned;
      const unsigned bit = 1u << (W * (hx % W) + hy % W);
      if (!next.empty() && next.back().ra == hx / W && next.back().rb == hy / W)
        next.back().cut = std::uint16_t(next.back().cut | bit);  // its quiet flag stands: (x, y) is quiet
      else
        next.push_back(WideFrontGroup{hx / W, hy / W, std::uint16_t(bit), 1});
    }
  };
  for (const WideFrontGroup* g = begin; g != end; ++g) {
    // Lane pairs inside a patch that cannot touch itself this step: kept, untested.
    unsigned held = 0;
    if (v.skip_root)
      for (unsigned m = g->cut; m; m &= m - 1) {
        const int bit = std::countr_zero(m);
        if (v.in_skipped_patch(la.lanes[std::size_t(g->ra)].node[std::size_t(bit / W)],
                               lb.lanes[std::size_t(g->rb)].node[std::size_t(bit % W)]))
          held |= 1u << bit;
      }
    const unsigned allowed = g->cut & ~held;
    ++c.visited;
    c.bv_tests += unsigned(std::popcount(allowed));
    room_for_visit();
    const LanePairAnswer kept = visit_lane_pairs(wide_a[g->ra], wide_b[g->rb], g->ra, g->rb, allowed, self, cur);
    c.sprouted += unsigned(std::popcount(kept.down));
    push_group(g->ra, g->rb, g->cut & ~kept.down & ~kept.adjacent, kept.hit == 0 && held == 0);
    // Sprouts: the walk below every lane pair pushed, each visit leaving the group of what it did not descend.
    while (cur.top > 0) {
      --cur.top;
      const Index ha = cur.col_ha[cur.top], hb = cur.col_hb[cur.top], wa = cur.col_wa[cur.top], wb = cur.col_wb[cur.top];
      if (cur.top >= 2) prefetch_entry_records(wide_a, wide_b, cur, cur.top - 2);
      Index ra, rb;
      const unsigned lanes = entry_lane_pairs(wide_a, wide_b, ha, hb, wa, wb, ra, rb);
      c.bv_tests += unsigned(std::popcount(lanes));
      room_for_visit();
      const LanePairAnswer a = visit_lane_pairs(wide_a[ra], wide_b[rb], ra, rb, lanes, self, cur);
      push_group(ra, rb, lanes & ~a.down & ~a.adjacent, false);
    }
    // The next group's records, asked for early (the front is read in order; its records are scattered).
    if (g + 2 < end) {
      const char* ra = reinterpret_cast<const char*>(wide_a + g[2].ra);
      const char* rb = reinterpret_cast<const char*>(wide_b + g[2].rb);
      for (std::size_t line = 0; line < sizeof(WideBounds<BV>); line += 64) __builtin_prefetch(ra + line), __builtin_prefetch(rb + line);
    }
  }
  pairs.resize(std::size_t(cur.pout - pairs.data()));
  counters.bv_tests += c.bv_tests;
  counters.visited += c.visited;
  counters.sprouted += c.sprouted;
  counters.pruned += c.pruned;
}
#endif

}  // namespace ccdlab
