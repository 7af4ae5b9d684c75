#pragma once
// Splitting the BVTT into independent tasks and running them on threads: what `phc` and `static` share.
//   expand_breadth_first : the serial top — breadth-first from the root until a level holds ≥ `want` nodes
//                          (self nodes open into 3 children, overlapping pair nodes into 2; leaf pairs found
//                          on the way are candidates already)
//   run_bvtt_tasks        : each task is a depth-first traversal below its node, into its thread's part of
//                          the candidate list
#include <algorithm>
#include <chrono>

#include "framework/traversal/bvtt.hpp"
#include "framework/traversal/scheduler.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

template <class BV>
std::vector<BvttNode> expand_breadth_first(const BvttView<BV>& v, std::size_t want, TraversalOutput& out,
                                           BvttNode root = {0, 0}) {
  const auto& na = v.side_a.bvh->nodes;
  const auto& nb = v.side_b.bvh->nodes;
  std::vector<BvttNode> level{root}, next;
  while (!level.empty() && level.size() < want) {
    next.clear();
    bool opened = false;
    for (BvttNode n : level) {
      const BvhNode& A = na[n.a];
      const auto open = [&](const typename BvttView<BV>::Children& c) {
        next.insert(next.end(), c.node, c.node + c.count);
        opened = true;
      };
      if (v.self && n.a == n.b) {
        if (v.self_opens(A, n.a)) open(v.self_children(A));
        continue;
      }
      ++out.bv_tests;
      if (!v.nodes_overlap(n.a, n.b)) continue;
      const BvhNode& B = nb[n.b];
      if (A.is_leaf() && B.is_leaf()) {
        v.emit_leaf_pair(A, B, out.pairs.part(0));
        continue;
      }
      open(v.pair_children(n));
    }
    std::swap(level, next);
    if (!opened) break;
  }
  return level;
}

/// What a pass's tasks cost at the last step, so that the next step hands out the largest first (`phc`).
/// Dynamic scheduling in the breadth-first order lets a large task start last, and one thread then idles while
/// the other finishes it. A steady simulation cuts the same tasks step after
/// step (same topology, same top of the BVTT) at similar costs, so last step's costs order this step's tasks
/// (longest processing time first: the tail is the smallest tasks). Any other task list runs in its own order.
/// The order changes which thread finds which candidates, never which are found.
class TaskCosts {
 public:
  /// The order to hand `tasks` out in: largest last cost first when they are the last step's tasks; else theirs.
  [[nodiscard]] std::vector<std::size_t> order(const std::vector<BvttNode>& tasks) const {
    std::vector<std::size_t> order(tasks.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    if (same_as_last(tasks))  // stable: equal costs keep the breadth-first order
      std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return ms_[x] > ms_[y]; });
    return order;
  }
  /// The threads of `tasks`, fixed before the start (`static`): by their last costs, largest first to the least
  /// loaded thread, when they are the last step's tasks (`balanced` set); else none (equal-count chunks).
  [[nodiscard]] std::vector<int> assignment(const std::vector<BvttNode>& tasks, int threads, bool& balanced) const {
    balanced = same_as_last(tasks);
    return balanced ? assign_largest_first(ms_, threads) : std::vector<int>{};
  }
  /// Keeps the costs of `tasks`, handed out in `order`: task_ms[i] is the cost of tasks[order[i]].
  void record(const std::vector<BvttNode>& tasks, const std::vector<std::size_t>& order, const std::vector<double>& task_ms) {
    tasks_ = tasks;
    ms_.assign(tasks.size(), 0.0);
    for (std::size_t i = 0; i < order.size(); ++i) ms_[order[i]] = task_ms[i];
  }

 private:
  [[nodiscard]] bool same_as_last(const std::vector<BvttNode>& tasks) const {
    return tasks.size() == tasks_.size() &&
           std::equal(tasks.begin(), tasks.end(), tasks_.begin(),
                      [](const BvttNode& x, const BvttNode& y) { return x.a == y.a && x.b == y.b; });
  }
  std::vector<BvttNode> tasks_;
  std::vector<double> ms_;
};

/// Runs a depth-first traversal below each task on `threads` threads: dynamically (one task at a time to
/// whichever thread is free, tasks[order[0]] first), in `threads` equal-count contiguous chunks fixed before
/// the start, or on the threads `thread_of` fixes (static_balanced: thread_of[i] runs tasks[order[i]]). Thread t
/// appends to part t of out.pairs, and hands it over after each task. trace.task_ms[i] is the cost of
/// tasks[order[i]].
template <class BV>
void run_bvtt_tasks(const BvttView<BV>& v, const std::vector<BvttNode>& tasks, const std::vector<std::size_t>& order,
                    int threads, Distribution dist, TraversalOutput& out, PhaseTrace& trace,
                    const std::vector<int>* thread_of = nullptr) {
  struct Local {
    std::uint64_t bv_tests = 0;
    BvttStack stack;
  };
  std::vector<PerThread<Local>> local(threads);
  out.pairs.use_parts(threads);
  parallel_tasks(
      tasks.size(), threads, dist, trace,
      [&](std::size_t i, int tid) {
        Local& l = local[tid].value;
        traverse_bvtt(v, tasks[order[i]], l.stack, out.pairs.part(tid), l.bv_tests);
        out.hand_over(tid);
      },
      thread_of);
  for (const auto& l : local) out.bv_tests += l.value.bv_tests;
}

}  // namespace ccdlab

namespace ccdlab {

/// Breadth-first split of the pass's BVTT into ≥ tasks_per_thread·split_threads tasks (serial, timed as the trace's
/// serial part), then the tasks on threads. Shared by `phc` (dynamic, ordered by `costs`, which it updates) and
/// `static` (dist static_balanced: fixed before the start, by `costs` when they are the last step's tasks, else
/// equal-count chunks in breadth-first order).
inline void split_and_run(const TraversalPass& pass, int tasks_per_thread, Distribution dist, const char* phase,
                          TraversalOutput& out, std::vector<PhaseTrace>& traces, TaskCosts* costs = nullptr) {
  if (pass.side_a.bvh->nodes.empty() || pass.side_b.bvh->nodes.empty()) return;
  with_bvtt_view(pass, [&](const auto& view) {
    PhaseTrace trace{phase, dist, 0, {}, {}};
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t want = std::size_t(tasks_per_thread) * std::size_t(pass.split_threads);
    std::vector<BvttNode> tasks = expand_breadth_first(view, want, out, pass.root);
    const double serial = ms_between(t0, std::chrono::steady_clock::now());
    trace.serial_ms += serial;
    out.stats.serial_ms += serial;
    out.stats.tasks += tasks.size();
    std::vector<std::size_t> order;
    std::vector<int> thread_of;
    if (dist == Distribution::static_balanced) {
      bool balanced = false;
      thread_of = costs ? costs->assignment(tasks, pass.threads, balanced) : std::vector<int>{};
      if (!balanced) dist = Distribution::static_chunks;
      order = TaskCosts().order(tasks);  // breadth-first
    } else {
      order = costs ? costs->order(tasks) : TaskCosts().order(tasks);
    }
    run_bvtt_tasks(view, tasks, order, pass.threads, dist, out, trace, &thread_of);
    if (costs) costs->record(tasks, order, trace.task_ms);
    traces.push_back(std::move(trace));
  });
}

}  // namespace ccdlab
