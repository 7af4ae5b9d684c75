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

/// One traversal pass of a step: a BVH against itself (self-collision) or against another body's BVH.
/// `id` is stable across steps so stateful schedulers (e.g. a BVTT front) can keep per-pass data.
struct TraversalPass {
  int id = 0;
  const TriMesh* mesh = nullptr;
  const BvhTopology* bvh_a = nullptr;
  const AnyBvs* bvs_a = nullptr;
  const BvhTopology* bvh_b = nullptr;  ///< == bvh_a for self passes
  const AnyBvs* bvs_b = nullptr;
  bool self = true;
  int threads = 1;  ///< OpenMP threads the scheduler may use
  int split_threads = 1;  ///< threads a decomposition is cut for (== threads, except when bench records traces)
  const std::vector<Index>* skip_root = nullptr;  ///< normal-cone culling of self tests (self passes), or none
  /// The 4-wide views of both hierarchies (bv.width: 4), refit with the binary volumes; nullptr for width 2.
  /// traverse_bvtt walks them when both are there; the front scheduler keeps its binary front either way.
  const WideLayout* wide_layout_a = nullptr;
  const AnyWideBvs* wide_a = nullptr;
  const WideLayout* wide_layout_b = nullptr;
  const AnyWideBvs* wide_b = nullptr;
  /// End boxes (framework/swept/end_boxes.hpp) of both hierarchies' nodes, and of the wide records' lanes
  /// (width 4), or nullptr when the pipeline keeps none; the walks test them in the steps that set `test_ends`
  /// (the pipeline refits them in those steps only).
  const BvArray<EndBoxes>* ends_a = nullptr;
  const BvArray<EndBoxes>* ends_b = nullptr;
  const WideEndsArray* wide_ends_a = nullptr;
  const WideEndsArray* wide_ends_b = nullptr;
  bool test_ends = false;
  /// Where the traversal starts: the BVTT root, or one slice of it when a memory-bounded step streams its
  /// candidates to the narrow phase slice by slice (CcdPipeline; a slice has a negative `id`, released after it).
  BvttNode root{0, 0};
};

/// Calls f(BvttView<BV>) with the pass's volumes at their static type: the one place a scheduler dispatches on K.
template <class F>
void with_bvtt_view(const TraversalPass& pass, F&& f) {
  std::visit(
      [&](const auto& bvs_a) {
        using BV = typename std::decay_t<decltype(bvs_a)>::value_type;
        const auto& bvs_b = std::get<BvArray<BV>>(*pass.bvs_b);
        const Index* skip = pass.skip_root && !pass.skip_root->empty() ? pass.skip_root->data() : nullptr;
        BvttView<BV> view{pass.bvh_a, &bvs_a, pass.bvh_b, &bvs_b, pass.mesh, pass.self, skip};
        const bool ends = pass.test_ends && pass.ends_a && pass.ends_b;
        if (ends) view.ends_a = pass.ends_a->data(), view.ends_b = pass.ends_b->data();
        if (pass.wide_a && pass.wide_b) {
          view.wide_layout_a = pass.wide_layout_a;
          view.wide_a = &std::get<WideBvs<BV>>(*pass.wide_a);
          view.wide_layout_b = pass.wide_layout_b;
          view.wide_b = &std::get<WideBvs<BV>>(*pass.wide_b);
          view.lane_pairs = lane_pair_walk();
          if (ends && pass.wide_ends_a && pass.wide_ends_b)
            view.wide_ends_a = pass.wide_ends_a->data(), view.wide_ends_b = pass.wide_ends_b->data();
        }
        f(view);
      },
      *pass.bvs_a);
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
