#include "framework/export/bvtt_walk.hpp"

#include <algorithm>
#include <deque>

namespace ccdlab {
namespace {

/// One visit of node n with the traversal's rule; the children to visit next (in visiting order) into `next`.
template <class BV>
WalkVisit visit(const BvttView<BV>& v, BvttNode n, std::vector<BvttNode>& next) {
  next.clear();
  WalkVisit w{n.a, n.b};
  const BvhNode& A = v.side_a.bvh->nodes[n.a];
  if (v.self && n.a == n.b) {
    if (v.self_opens(A, n.a)) {
      const auto c = v.self_children(A);
      for (int i = 0; i < c.count; ++i) next.push_back(c.node[i]);
    }
    return w;
  }
  w.tested = true;
  w.overlap = v.nodes_overlap(n.a, n.b);
  if (!w.overlap) return w;
  const BvhNode& B = v.side_b.bvh->nodes[n.b];
  if (A.is_leaf() && B.is_leaf()) {
    FacePairs pair;
    w.candidate = v.emit_leaf_pair(A, B, pair);
    return w;
  }
  const auto c = v.pair_children(n);
  for (int i = 0; i < c.count; ++i) next.push_back(c.node[i]);
  return w;
}

/// Depth-first below n (pre-order, as traverse_bvtt_binary), appending to out with the given task and thread.
template <class BV>
void depth_first(const BvttView<BV>& v, BvttNode n, int task, int thread, long& clock, std::vector<WalkVisit>& out) {
  std::vector<BvttNode> stack{n}, next;
  while (!stack.empty()) {
    const BvttNode m = stack.back();
    stack.pop_back();
    WalkVisit w = visit(v, m, next);
    w.task = task, w.thread = thread, w.time = clock++;
    out.push_back(w);
    for (auto it = next.rbegin(); it != next.rend(); ++it) stack.push_back(*it);
  }
}

/// Tasks taken by the first free thread (ties: the lowest id); each task walks its nodes depth-first. The visits
/// are then ordered by simulated time.
template <class BV>
void run_tasks(const BvttView<BV>& v, const std::vector<std::vector<BvttNode>>& tasks, int threads, long start_time,
               BvttWalk& walk) {
  std::vector<long> clock(std::size_t(std::max(threads, 1)), start_time);
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    const int thread = int(std::min_element(clock.begin(), clock.end()) - clock.begin());
    for (const BvttNode& n : tasks[t]) depth_first(v, n, int(t), thread, clock[std::size_t(thread)], walk.visits);
  }
  std::stable_sort(walk.visits.begin(), walk.visits.end(), [](const WalkVisit& a, const WalkVisit& b) {
    return a.time != b.time ? a.time < b.time : a.thread < b.thread;
  });
  walk.tasks = int(tasks.size());
}

/// Whether BVH node x lies in the sub-tree of r (pre-order ranges).
bool below(const BvhTopology& bvh, Index r, Index x) { return x >= r && x < bvh.subtree_end(r); }

}  // namespace

BvttWalk walk_sequential(const TraversalPass& pass, BvttNode start) {
  BvttWalk walk{"sequential", 1, 0, {}};
  with_bvtt_view(pass, [&](const auto& v) {
    long clock = 0;
    depth_first(v, start, -1, 0, clock, walk.visits);
  });
  return walk;
}

BvttWalk walk_phc(const TraversalPass& pass, BvttNode start, int threads, int tasks_per_thread) {
  BvttWalk walk{"phc", threads, 0, {}};
  with_bvtt_view(pass, [&](const auto& v) {
    // The breadth-first top, on one thread, until there are enough open nodes to share.
    std::deque<BvttNode> open{start};
    std::vector<BvttNode> next;
    long clock = 0;
    const std::size_t enough = std::size_t(std::max(1, tasks_per_thread * threads));
    while (!open.empty() && open.size() < enough) {
      const BvttNode n = open.front();
      open.pop_front();
      WalkVisit w = visit(v, n, next);
      w.time = clock++;
      walk.visits.push_back(w);
      for (const BvttNode& c : next) open.push_back(c);
    }
    std::vector<std::vector<BvttNode>> tasks;
    for (const BvttNode& n : open) tasks.push_back({n});
    run_tasks(v, tasks, threads, clock, walk);
  });
  return walk;
}

BvttWalk walk_front(const TraversalPass& pass, BvttNode start, const std::vector<FrontNode>& front, int threads, int chunk) {
  BvttWalk walk{"front", threads, 0, {}};
  with_bvtt_view(pass, [&](const auto& v) {
    std::vector<std::vector<BvttNode>> tasks;
    for (const FrontNode& f : front) {
      if (!below(*pass.side_a.bvh, start.a, f.a) || !below(*pass.side_b.bvh, start.b, f.b)) continue;
      if (tasks.empty() || int(tasks.back().size()) == std::max(chunk, 1)) tasks.emplace_back();
      tasks.back().push_back({f.a, f.b});
    }
    if (tasks.empty()) tasks.push_back({start});  // no front yet (a first step): the walk starts at the top
    run_tasks(v, tasks, threads, 0, walk);
  });
  return walk;
}

}  // namespace ccdlab
