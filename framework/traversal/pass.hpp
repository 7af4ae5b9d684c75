#pragma once
// One traversal pass of a step (a BVH against itself, or two bodies' BVHs) and the one place a walk gets the
// pass's volumes at their static type (with_bvtt_view): the K is chosen at run time (bv.k), the kernels are
// templates, so a scheduler dispatches once per call, never per node.
#include <vector>

#include "framework/hierarchy/pass_side.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/traversal/bvtt.hpp"

namespace ccdlab {

/// One traversal pass of a step: a BVH against itself (self-collision) or against another body's BVH.
/// `id` is stable across steps so stateful schedulers (e.g. a BVTT front) can keep per-pass data.
struct TraversalPass {
  int id = 0;
  const TriMesh* mesh = nullptr;
  PassSide side_a;
  PassSide side_b;  ///< == side_a for self passes
  bool self = true;
  int threads = 1;  ///< OpenMP threads the scheduler may use
  int split_threads = 1;  ///< threads a decomposition is cut for (== threads, except when bench records traces)
  const std::vector<Index>* skip_root = nullptr;  ///< normal-cone culling of self tests (self passes), or none
  /// Whether the walks test the end boxes in this step (the pipeline refits them in those steps only).
  bool test_ends = false;
  /// Where the traversal starts: the BVTT root, or one slice of it when a memory-bounded step streams its
  /// candidates to the narrow phase slice by slice (CcdPipeline; a slice has a negative `id`, released after it).
  BvttNode root{0, 0};
};

/// A side's arrays at their static type BV (`ends`: whether this step tests end boxes).
template <class BV>
BvttSide<BV> bvtt_side(const PassSide& s, bool ends) {
  BvttSide<BV> out{s.bvh, &std::get<BvArray<BV>>(*s.bvs)};
  if (ends && s.ends) out.ends = s.ends->data();
  if (s.wide) {
    out.wide_layout = s.wide_layout;
    out.wide = &std::get<WideBvs<BV>>(*s.wide);
    if (ends && s.ends && s.wide_ends) out.wide_ends = s.wide_ends->data();
  }
  return out;
}

/// Calls f(BvttView<BV>) with the pass's volumes at their static type: the one place a scheduler dispatches on K.
template <class F>
void with_bvtt_view(const TraversalPass& pass, F&& f) {
  std::visit(
      [&](const auto& bvs_a) {
        using BV = typename std::decay_t<decltype(bvs_a)>::value_type;
        const Index* skip = pass.skip_root && !pass.skip_root->empty() ? pass.skip_root->data() : nullptr;
        // End boxes only where both sides keep them; a wide walk only where both sides have the wide view.
        const bool ends = pass.test_ends && pass.side_a.ends && pass.side_b.ends;
        BvttView<BV> view{bvtt_side<BV>(pass.side_a, ends), bvtt_side<BV>(pass.side_b, ends), pass.mesh, pass.self, skip};
        if (!(view.side_a.wide && view.side_b.wide)) {
          view.side_a.wide = view.side_b.wide = nullptr;
          view.side_a.wide_layout = view.side_b.wide_layout = nullptr;
          view.side_a.wide_ends = view.side_b.wide_ends = nullptr;
        } else if (!(view.side_a.wide_ends && view.side_b.wide_ends)) {
          view.side_a.wide_ends = view.side_b.wide_ends = nullptr;
        }
        view.lane_pairs = view.wide() ? lane_pair_walk() : LanePairWalk::none;
        f(view);
      },
      *pass.side_a.bvs);
}

}  // namespace ccdlab
