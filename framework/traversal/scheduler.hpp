#pragma once
// TraversalScheduler: decides how the BVTT is traversed (sequentially, split into parallel tasks, from a
// front kept across steps, …). Every scheduler must yield exactly the same candidate set as `sequential`.
// The BV type is chosen at run time (bv.k) but the kernels are templates: a scheduler receives an AnyBvs
// variant and dispatches once per call (std::visit), never per node.
#include <memory>
#include <string_view>
#include <variant>
#include <vector>

#include "framework/geometry/kdop.hpp"
#include "framework/hierarchy/bvh.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/traversal/bvtt.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/util/error.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

/// A hierarchy's node bounds, whichever K it uses (KdopKs).
using AnyBvs = KdopVariant<BvArray>;
/// The 4-wide bounds of the same hierarchy (bv.width: 4), same alternative as its AnyBvs.
using AnyWideBvs = KdopVariant<WideBvs>;

/// An AnyBvs / AnyWideBvs holding an empty array of KDop<k>; throws Error unless is_kdop_k(k).
inline AnyBvs make_bvs(int k) {
  if (auto v = empty_kdop_variant<BvArray>(k)) return std::move(*v);
  fail("bv.k: expected one of {}, got {}", kKdopKs, k);
}
inline AnyWideBvs make_wide_bvs(int k) {
  if (auto v = empty_kdop_variant<WideBvs>(k)) return std::move(*v);
  fail("bv.k: expected one of {}, got {}", kKdopKs, k);
}

/// One hierarchy of a pass as the pipeline hands it over: its topology and node volumes and, where the pipeline
/// keeps them, its 4-wide view (bv.width: 4, refit with the binary volumes) and end boxes (framework/swept/
/// end_boxes.hpp, of the nodes and of the wide records' lanes). BodyHierarchy::side fills one in.
struct PassSide {
  const BvhTopology* bvh = nullptr;
  const AnyBvs* bvs = nullptr;
  const WideLayout* wide_layout = nullptr;
  const AnyWideBvs* wide = nullptr;
  const BvArray<EndBoxes>* ends = nullptr;
  const WideEndsArray* wide_ends = nullptr;
};

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

class TraversalScheduler {
 public:
  virtual ~TraversalScheduler() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// Appends the candidate face pairs of the pass to out (order unspecified), counts BV tests in out.bv_tests
  /// and its other work in out.stats, and appends the trace of its parallel part to `traces`.
  virtual void collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) = 0;
  /// Drops whatever state was kept for pass `id` across steps (a BVTT front): memory-bounded steps release
  /// each slice's state once its candidates are tested. Stateless schedulers keep nothing.
  virtual void release(int /*pass_id*/) {}
  /// True when the tasks depend on the thread count (phc and static cut c·threads tasks): the simulator must
  /// then replay, for N cores, a run split for N threads (TraversalPass::split_threads), not the 1-thread split.
  [[nodiscard]] virtual bool splits_by_threads() const { return false; }
};

}  // namespace ccdlab
