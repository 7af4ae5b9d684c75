#pragma once
// The walks over the 4-wide view (bv.width: 4; framework/hierarchy/wide_bvh.hpp, docs/wide-bvh.md), one header
// each; both make the binary BVTT's candidates (see wide_bvh.hpp for why skipping levels keeps them):
//   traverse_bvtt_lane_pairs — AVX-512 or AVX2: a pair node opens both sides' records and tests their 4 × 4 lane
//                              pairs in one 16-lane compare per axis (two 8-lane ones in AVX2); no branch on the
//                              answers (compress-stores; table permutations in AVX2). lane_pair_walk_avx512.hpp,
//                              lane_pair_walk_avx2.hpp, their stack lane_pair_stack.hpp; dispatched here.
//   traverse_bvtt_wide       — any x86-64 (SSE2): a pair node opens its larger side's record and tests its four
//                              lanes against the other side; the walk for CPUs without AVX2. wide_walk.hpp.
#include "framework/traversal/bvtt_view.hpp"
#include "framework/traversal/lane_pair_stack.hpp"
#include "framework/traversal/lane_pair_walk_avx2.hpp"
#include "framework/traversal/lane_pair_walk_avx512.hpp"
#include "framework/traversal/wide_walk.hpp"

namespace ccdlab {

#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
/// The lane-pair walk of `walk` (not none).
template <class BV>
void traverse_bvtt_lane_pairs(LanePairWalk walk, const BvttView<BV>& v, BvttNode start, LanePairStack& stack,
                              FacePairs& pairs, std::uint64_t& bv_tests) {
  if (walk == LanePairWalk::avx512) lane_pair_avx512::traverse_bvtt_lane_pairs(v, start, stack, pairs, bv_tests);
  else lane_pair_avx2::traverse_bvtt_lane_pairs(v, start, stack, pairs, bv_tests);
}
#endif

}  // namespace ccdlab
