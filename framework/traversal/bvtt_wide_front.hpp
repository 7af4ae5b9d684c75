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
//   PRUNE   a carried-over group none of whose lane pairs overlaps, whose mask is every lane pair of one node
//           pair's visit (all used lanes of a record whose owner is x, or the one lane of a leaf x; likewise y;
//           not two single leaves, which is the node itself), is replaced by that node pair (x, y) when (x, y)
//           does not overlap either: its lane pair in the records holding x and y, merged into the group just
//           written when that is the same two records, which may prune in turn. (x, y) covers exactly the
//           group's leaf pairs, so the cut stays a cut. (x, y)'s answer is usually known already: it is a lane
//           pair of the visit that made the group, whose 16 answers a small cache of this step's visits keeps
//           (else one BV test); after a failed attempt the group waits kPruneWait steps, and so does a group a
//           sprout wrote (its node pair overlapped: it was descended).
//   REBUILD from seeds (wide_front_seeds). In a self pass whose step skips no patch (normal cones), the seeds
//           below some depth are SELF NODES, lane pair (i, i) of one record: not node pairs on a cut but
//           sub-trees the first step walks as traverse_bvtt_lane_pairs does (a self node opens into (L, L),
//           (R, R) and (L, R) untested), so that step is that walk plus the groups it writes. Seeding with the
//           node pairs (L, R) of every inner node instead — the binary front's way, still used where patches are
//           skipped — made it a walk of thousands of shallow sprouts whose first record reads all missed
//           (docs/results-scheduling.md). Every self seed is opened in that step (none is in a skipped patch), so
//           no self node is ever on the cut after it.
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
  std::uint8_t quiet;       ///< while a step writes it: carried over, none of its lane pairs overlapped (may prune)
  std::uint8_t prune_wait;  ///< steps before its next prune attempt (its node pair overlapped at the last one)
};
/// Steps a group waits after a failed prune attempt: attempting at every step was a large part of the steady
/// front's cost (docs/results-scheduling.md); a wait delays a prune by at most this many steps, never an answer.
inline constexpr std::uint8_t kPruneWait = 8;
/// The wait of a group that is no node pair's whole visit: until its mask changes (which resets every wait), or
/// this many steps.
inline constexpr std::uint8_t kNoPruneWhileSame = 255;
/// The lane pairs (i, i) of a group: in a self pass, with one record on both sides, the self nodes (x, x).
inline constexpr unsigned kDiagonalLanePairs = 0x8421u;
/// A piece of the front, written in place (uninitialized growth: a piece is rewritten whole every step).
using WideFrontPiece = UninitializedVector<WideFrontGroup>;
static_assert(sizeof(WideFrontGroup) == 12, "a group is 3 words: keep the front compact");

/// The front a rebuild starts from, covering the BVTT below `root` (the whole BVTT, or one slice): (L, R) for
/// every inner node under a self node, the node itself otherwise, each split into the lane pairs of its visit
/// (without a BV test: they cover the same leaf pairs) until it covers at most 1/`granularity` of the pass's leaf
/// pairs (and no fewer than `min_pairs`), so that the first step's sprouts are spread over many tasks.
/// With `self_nodes` (a self pass's step that skips no patch), a self node covering that many leaf pairs or
/// fewer is a seed itself, lane pair (i, i) of the record holding it, and the nodes below it seed nothing.
WideFrontPiece wide_front_seeds(const BvhTopology& a, const WideLayout& la, const BvhTopology& b,
                                const WideLayout& lb, bool self, BvttNode root = {0, 0}, bool self_nodes = false,
                                double granularity = 512, double min_pairs = 4096);

/// The front's cut node pairs as binary node ids (flags 0), appended to `out`: for tests and `ccdlab export`.
void append_wide_front_nodes(const WideLayout& la, const WideLayout& lb, const WideFrontGroup* begin,
                             const WideFrontGroup* end, std::vector<FrontNode>& out);

#if defined(CCDLAB_HAS_AVX512_WALK)
/// Processes groups [begin, end) (AVX-512: call only where the view's lane_pairs is set): appends the next
/// front's groups to `next` and the candidates to `pairs`. `prune`: false at a rebuild (seeds are split for
/// balance, not to be merged back at once) or when the scheduler says so. The groups of `next` before
/// `piece_begin` are other pieces': nothing is merged into them.
template <class BV>
CCDLAB_AVX512_TARGET void process_wide_front(const BvttView<BV>& v, const WideFrontGroup* begin,
                                             const WideFrontGroup* end, bool prune, WideFrontPiece& next,
                                             std::size_t piece_begin, FacePairs& pairs, LanePairStack& stack,
                                             FrontCounters& counters) {
  constexpr int W = WideLayout::kWidth;
  const WideBounds<BV>* const wide_a = v.wide_a->data();
  const WideBounds<BV>* const wide_b = v.wide_b->data();
  const WideLayout& la = *v.wide_layout_a;
  const WideLayout& lb = *v.wide_layout_b;
  const BvhNode* const na = v.bvh_a->nodes.data();
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
  // The homes of the node pair whose visit tests exactly g's lane pairs (see PRUNE above), or false. No
  // sub-tree test is needed in self passes: a cut holds pair nodes only, and if x held y (or x == y) some lane
  // pair of x's record and y's would hold one side inside the other.
  const auto whole_visit_of = [&](const WideFrontGroup& g, Index& hx, Index& hy) {
    const unsigned cut = g.cut;
    unsigned rows = 0;
    for (int i = 0; i < W; ++i) rows |= unsigned((cut >> (W * i) & 0xFu) != 0) << i;
    const unsigned cols = (cut | cut >> 4 | cut >> 8 | cut >> 12) & 0xFu;
    if (cut != (lane_rows_mask(rows) & (cols * 0x1111u))) return false;
    const auto side = [&](const WideLayout& l, const WideBounds<BV>& rec, Index r, unsigned lanes, Index& h) {
      if (lanes == (1u << used_lanes(rec)) - 1) {  // every lane: the record's owner (the top record is nobody's)
        h = l.owner_home[std::size_t(r)];
        return h >= 0 ? 1 : -1;
      }
      const int j = std::countr_zero(lanes);
      if (std::popcount(lanes) != 1 || rec.lanes.slot[std::size_t(j)] >= 0) return -1;
      h = r * W + j;  // a leaf side stays itself
      return 0;
    };
    const int inner_a = side(la, wide_a[g.ra], g.ra, rows, hx);
    const int inner_b = side(lb, wide_b[g.rb], g.rb, cols, hy);
    return inner_a >= 0 && inner_b >= 0 && inner_a + inner_b > 0;
  };
  // The next front's groups: written in place like the candidates (at most one more per visit).
  std::size_t written = next.size();
  next.resize(std::max<std::size_t>(next.capacity(), written + 256));
  WideFrontGroup* gbase = next.data();
  WideFrontGroup* gout = gbase + written;
  WideFrontGroup* gfloor = gbase + piece_begin;  // the first group of this piece: merges stop there
  WideFrontGroup* gend = gbase + next.size();
  const auto room_for_group = [&] {
    if (gout == gend) [[unlikely]] {
      written = std::size_t(gout - gbase);
      next.resize(2 * next.size());
      gbase = next.data(), gout = gbase + written, gend = gbase + next.size(), gfloor = gbase + piece_begin;
    }
  };
  // This step's recent visits: their records and all 16 answers, direct-mapped (the answers cannot change within
  // a step). A quiet group's parent visit is usually among them.
  struct Seen {
    Index ra = -1, rb = -1;
    unsigned all = 0;
  };
  constexpr unsigned kSeen = 256;
  Seen seen[kSeen];
  const auto seen_slot = [](Index ra, Index rb) { return (unsigned(ra) * 2654435761u + unsigned(rb)) >> 24 & (kSeen - 1); };
  const auto remember = [&](Index ra, Index rb, unsigned all) { seen[seen_slot(ra, rb)] = Seen{ra, rb, all}; };
  // Does the lane pair at homes hx, hy overlap? From the cache, else one BV test.
  const auto lane_pair_overlaps = [&](Index hx, Index hy) {
    const Seen& s = seen[seen_slot(hx / W, hy / W)];
    if (s.ra == hx / W && s.rb == hy / W) return (s.all >> (W * (hx % W) + hy % W) & 1u) != 0;
    ++c.bv_tests;
    return (overlapping_lanes(wide_b[hy / W], WideLane<BV>{wide_a + hx / W, hx % W}) >> (hy % W) & 1u) != 0;
  };
  // Appends a group, merged into the last one when it holds the same two records; then, while the last group is
  // quiet and is one node pair's whole visit, and that node pair does not overlap, prunes it into that node pair.
  const auto push_group = [&](Index ra, Index rb, unsigned cut, bool quiet, std::uint8_t wait) {
    if (!cut) return;
    if (gout != gfloor && gout[-1].ra == ra && gout[-1].rb == rb) {
      gout[-1].cut = std::uint16_t(gout[-1].cut | cut);
      gout[-1].quiet &= std::uint8_t(quiet);
      gout[-1].prune_wait = std::min(gout[-1].prune_wait, wait);
    } else {
      room_for_group();
      *gout++ = WideFrontGroup{ra, rb, std::uint16_t(cut), std::uint8_t(quiet), wait};
    }
    while (prune && gout[-1].quiet && gout[-1].prune_wait == 0) {
      Index hx, hy;
      if (!whole_visit_of(gout[-1], hx, hy)) {  // not one node pair's visit until its mask changes
        gout[-1].prune_wait = kNoPruneWhileSame;
        break;
      }
      if (lane_pair_overlaps(hx, hy)) {
        gout[-1].prune_wait = kPruneWait;
        break;
      }
      --gout;
      ++c.pruned;
      const unsigned bit = 1u << (W * (hx % W) + hy % W);
      if (gout != gfloor && gout[-1].ra == hx / W && gout[-1].rb == hy / W) {
        gout[-1].cut = std::uint16_t(gout[-1].cut | bit);  // its quiet flag stands: (x, y) is quiet
        gout[-1].prune_wait = 0;  // a new mask: its own node pair may be whole now
      } else {
        *gout++ = WideFrontGroup{hx / W, hy / W, std::uint16_t(bit), 1, 0};
      }
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
    // Self seeds (a rebuild's only: see REBUILD), pushed for the walk below; the rest is visited.
    const unsigned self_seeds = self && g->ra == g->rb ? g->cut & kDiagonalLanePairs : 0;
    const unsigned allowed = g->cut & ~held & ~self_seeds;
    ++c.visited;
    c.bv_tests += unsigned(std::popcount(allowed));
    for (unsigned m = self_seeds; m; m &= m - 1) {
      const Index x = la.lanes[std::size_t(g->ra)].node[std::size_t(std::countr_zero(m) / W)];
      room_for_visit();
      cur.col_ha[cur.top] = cur.col_hb[cur.top] = x, cur.col_wa[cur.top] = cur.col_wb[cur.top] = -1;
      ++cur.top;
    }
    room_for_visit();
    const LanePairAnswer kept = visit_lane_pairs(wide_a[g->ra], wide_b[g->rb], g->ra, g->rb, allowed, self, cur);
    remember(g->ra, g->rb, kept.all);
    c.sprouted += unsigned(std::popcount(kept.down | self_seeds));
    const unsigned cut = g->cut & ~kept.down & ~kept.adjacent & ~self_seeds;
    const std::uint8_t wait = cut != g->cut || g->prune_wait == 0 ? 0 : std::uint8_t(g->prune_wait - 1);
    push_group(g->ra, g->rb, cut, kept.hit == 0 && held == 0 && wait == 0, wait);
    // Sprouts: the walk below every lane pair pushed, each visit leaving the group of what it did not descend.
    while (cur.top > 0) {
      --cur.top;
      const Index ha = cur.col_ha[cur.top], hb = cur.col_hb[cur.top], wa = cur.col_wa[cur.top], wb = cur.col_wb[cur.top];
      if (cur.top >= 2) prefetch_entry_records(wide_a, wide_b, cur, cur.top - 2);
      if (self && ha == hb) {  // a self node (by node id, as the walk pushes it; a pair node's homes differ)
        // Self seeds exist only where no patch is skipped, so self_opens is "not a leaf" here (else a skipped
        // node would leave the cut).
        if (const BvhNode& x = na[ha]; v.self_opens(x, ha)) {
          // As traverse_bvtt_lane_pairs: (L, R) untested, (R, R), then (L, L) on top.
          const auto push = [&](Index h_a, Index h_b, Index w_a, Index w_b) {
            cur.col_ha[cur.top] = h_a, cur.col_hb[cur.top] = h_b, cur.col_wa[cur.top] = w_a, cur.col_wb[cur.top] = w_b;
            ++cur.top;
          };
          room_for_visit();
          push(la.home[std::size_t(x.left)], la.home[std::size_t(x.right)], la.slot[std::size_t(x.left)], la.slot[std::size_t(x.right)]);
          push(x.right, x.right, -1, -1);
          push(x.left, x.left, -1, -1);
        }
        continue;
      }
      Index ra, rb;
      const unsigned lanes = entry_lane_pairs(wide_a, wide_b, ha, hb, wa, wb, ra, rb);
      c.bv_tests += unsigned(std::popcount(lanes));
      room_for_visit();
      const LanePairAnswer a = visit_lane_pairs(wide_a[ra], wide_b[rb], ra, rb, lanes, self, cur);
      remember(ra, rb, a.all);
      // Born waiting: its node pair overlapped this step (it was descended), so an attempt next step would fail
      // and cost a BV test on a record no visit has in cache (the binary front's kFresh rule).
      push_group(ra, rb, lanes & ~a.down & ~a.adjacent, false, kPruneWait);
    }
    // The next group's records, asked for early (the front is read in order; its records are scattered).
    if (g + 5 < end) {
      const char* ra = reinterpret_cast<const char*>(wide_a + g[5].ra);
      const char* rb = reinterpret_cast<const char*>(wide_b + g[5].rb);
      for (std::size_t line = 0; line < sizeof(WideBounds<BV>); line += 64) __builtin_prefetch(ra + line), __builtin_prefetch(rb + line);
    }
  }
  pairs.resize(std::size_t(cur.pout - pairs.data()));
  next.resize(std::size_t(gout - gbase));
  counters.bv_tests += c.bv_tests;
  counters.visited += c.visited;
  counters.sprouted += c.sprouted;
  counters.pruned += c.pruned;
}
#endif

}  // namespace ccdlab
