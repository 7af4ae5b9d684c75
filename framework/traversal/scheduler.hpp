#pragma once
// TraversalScheduler: decides how the BVTT is traversed (sequentially, split into parallel tasks, from a
// front kept across steps, …). Every scheduler must yield exactly the same candidate set as `sequential`.
// A scheduler is handed a TraversalPass (pass.hpp) and walks it with the one kernel (with_bvtt_view).
#include <memory>
#include <string_view>
#include <vector>

#include "framework/traversal/candidates.hpp"
#include "framework/traversal/pass.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

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
