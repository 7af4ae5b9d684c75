#pragma once
// Stage 3 of a step (design.md): the BVTT traversal of every pass, and its candidates into the narrow phase.
//   passes     self passes first, then body pairs; ids stable for the pipeline's lifetime (a stateful
//              scheduler, `front` or `static`, keys its state on them)
//   plan       the memory budget (memory_budget.hpp): the whole pass at once, or slice by slice
//   at once    the scheduler walks each pass; each thread hands its candidates to the narrow phase on the same
//              thread as it finds them (TraversalOutput::hand_over), and what is left is tested after
//   streamed   each pass cut into slices (one breadth-first level of the BVTT), each walked on its own, its
//              scheduler state released after it, and the candidates tested whenever a flush's worth is buffered
#include <vector>

#include "framework/pipeline/memory_budget.hpp"
#include "framework/pipeline/narrow_driver.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

class TraversalDriver {
 public:
  TraversalDriver(TraversalScheduler& scheduler, int threads, MemoryBudget budget)
      : scheduler_(scheduler), threads_(threads), budget_(budget) {}

  void add_pass(const TraversalPass& pass) { passes_.push_back(pass); }
  [[nodiscard]] const std::vector<TraversalPass>& passes() const { return passes_; }
  /// Whether the next runs test the passes' end boxes (TraversalPass::test_ends).
  void test_end_boxes(bool on) {
    for (TraversalPass& pass : passes_) pass.test_ends = on;
  }

  /// The next step's candidates as estimated before its traversal: its memory plan predicts at least these.
  void expect_candidates(double pairs) { budget_.expect(pairs); }
  /// Traverses every pass over a mesh of `faces` triangles and tests its candidates with `narrow`: timings
  /// traverse_ms and narrow_ms, the traversal's counters and the memory plan go to `result`.
  void run(std::size_t faces, const NarrowDriver& narrow, StepResult& result);

  /// Keep every candidate of a step (last_candidates) instead of handing them to the narrow phase as found.
  void keep_candidates(bool on) { keep_candidates_ = on; }
  [[nodiscard]] bool keeps_candidates() const { return keep_candidates_; }
  void set_hand_over_pairs(std::size_t pairs) { candidates_.hand_over_pairs = std::max<std::size_t>(1, pairs); }
  [[nodiscard]] const TraversalOutput& candidates() const { return candidates_; }

 private:
  /// Returns the traversal's ms (the narrow phase's time inside it left out).
  double run_at_once(const MemoryPlan& plan, const NarrowDriver& narrow, StepResult& result);
  double run_streamed(const MemoryPlan& plan, const NarrowDriver& narrow, StepResult& result);

  TraversalScheduler& scheduler_;
  int threads_;
  MemoryBudget budget_;
  std::vector<TraversalPass> passes_;
  TraversalOutput candidates_;
  bool keep_candidates_ = false;
};

}  // namespace ccdlab
