#pragma once
// The BVTT front on the 4-wide view (bv.width: 4 where the CPU has the lane-pair walk): the seed paper's front
// (front/binary_front.hpp) walked by the same kernel as every other scheduler, visit_lane_pairs (bvtt_wide.hpp).
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

#include "framework/traversal/front/binary_front.hpp"
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

#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
namespace lane_pair_avx512 {
#define CCDLAB_WALK_TARGET CCDLAB_AVX512_TARGET
#include "framework/traversal/front/wide_front_walk-inl.hpp"
#undef CCDLAB_WALK_TARGET
}  // namespace lane_pair_avx512
namespace lane_pair_avx2 {
#define CCDLAB_WALK_TARGET CCDLAB_AVX2_TARGET
#include "framework/traversal/front/wide_front_walk-inl.hpp"
#undef CCDLAB_WALK_TARGET
}  // namespace lane_pair_avx2

/// One step of the wide front on the lane-pair walk `walk` (not none): see wide_front_walk-inl.hpp.
template <class BV>
void process_wide_front(LanePairWalk walk, const BvttView<BV>& v, const WideFrontGroup* begin,
                        const WideFrontGroup* end, bool prune, WideFrontPiece& next, std::size_t piece_begin,
                        FacePairs& pairs, LanePairStack& stack, FrontCounters& counters) {
  if (walk == LanePairWalk::avx512)
    lane_pair_avx512::process_wide_front(v, begin, end, prune, next, piece_begin, pairs, stack, counters);
  else
    lane_pair_avx2::process_wide_front(v, begin, end, prune, next, piece_begin, pairs, stack, counters);
}
#endif

}  // namespace ccdlab
