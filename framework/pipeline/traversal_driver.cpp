#include "framework/pipeline/traversal_driver.hpp"

#include <algorithm>
#include <chrono>

#include "framework/traversal/bvtt_tasks.hpp"
#include "framework/util/memory.hpp"

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

void TraversalDriver::run(std::size_t faces, const NarrowDriver& narrow, StepResult& result) {
  // The step before's candidate pages are kept for this step's candidates while the step fits with them resident
  // (MemoryBudget::fits): freeing them at every step made each step fault and zero them again (docs/reliability.md,
  // "Memory").
  std::uint64_t resident = budget_.limit() > 0 ? current_rss_bytes() : 0;
  if (!budget_.fits(resident, faces)) {
    candidates_.pairs.release();
    if (budget_.limit() > 0) resident = current_rss_bytes();
  }
  const MemoryPlan plan = budget_.plan(resident, faces);
  // The contacts get as much room as the candidates (memory_budget.hpp, StepWatch::kBytesPerContact each).
  narrow.limit_contacts(budget_.limit() > 0 ? std::max<std::uint64_t>(1, plan.budget_bytes / StepWatch::kBytesPerContact) : 0);
  candidates_.clear();
  const double traverse_ms = plan.streamed ? run_streamed(plan, narrow, result) : run_at_once(plan, narrow, result);
  budget_.record(result.counters.candidate_pairs, candidates_.stats.front_bytes);
  result.memory.limit_bytes = budget_.limit();
  result.memory.slices = plan.streamed ? plan.slices : 0;

  result.counters.bv_tests = candidates_.bv_tests;
  const std::uint64_t culled = result.traversal.cone_culled, edges = result.traversal.contour_edges;
  result.traversal = candidates_.stats;
  result.traversal.bv_tests = candidates_.bv_tests;
  result.traversal.cone_culled = culled;
  result.traversal.contour_edges = edges;
  result.timings.traverse_ms = traverse_ms;
}

double TraversalDriver::run_at_once(const MemoryPlan& plan, const NarrowDriver& narrow, StepResult& result) {
  const auto t = Clock::now();
  candidates_.pairs.reserve(threads_, plan.expected_pairs);
  NarrowDriver::InTraversal taker(narrow);
  struct Unset {  // the consumer refers to this frame: never left set, even when a scheduler throws
    TraversalOutput& out;
    ~Unset() { out.consumer = nullptr; }
  } unset{candidates_};
  if (!keep_candidates_)
    candidates_.consumer = [&](int tid, std::span<const FacePair> pairs) { taker.take(tid, pairs); };
  for (const TraversalPass& pass : passes_) scheduler_.collect(pass, candidates_, result.traces);
  candidates_.consumer = nullptr;
  const double elapsed = ms_since(t);
  const double in_traversal = taker.finish(result);
  narrow.test_candidates(candidates_.pairs, result);  // what is left in the parts
  return elapsed - in_traversal;
}

double TraversalDriver::run_streamed(const MemoryPlan& plan, const NarrowDriver& narrow, StepResult& result) {
  double traverse_ms = 0;
  // A memory-bounded step keeps no scheduler state across steps: the pass's own is released too.
  for (const TraversalPass& pass : passes_) {
    scheduler_.release(pass.id);
    if (pass.side_a.bvh->nodes.empty() || pass.side_b.bvh->nodes.empty()) continue;
    auto t = Clock::now();
    std::vector<BvttNode> slices;
    with_bvtt_view(pass, [&](const auto& view) { slices = expand_breadth_first(view, plan.slices, candidates_); });
    traverse_ms += ms_since(t);
    for (const BvttNode& root : slices) {
      TraversalPass slice = pass;
      slice.root = root;
      slice.id = -1 - pass.id;  // never a kept pass's id
      t = Clock::now();
      scheduler_.collect(slice, candidates_, result.traces);
      scheduler_.release(slice.id);
      traverse_ms += ms_since(t);
      if (candidates_.pairs.size() >= plan.flush_pairs) {
        narrow.test_candidates(candidates_.pairs, result);
        candidates_.pairs.release();  // free, not just clear: the point is the memory
      }
    }
  }
  narrow.test_candidates(candidates_.pairs, result);
  return traverse_ms;
}

}  // namespace ccdlab
