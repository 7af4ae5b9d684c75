#pragma once
// The BVTT of one traversal pass expanded node by node in the order a scheduler's algorithm visits it, for the
// teaching page's walk-through (`ccdlab export --html`). The rule is the traversal's own (BvttView: self nodes
// open into three children, pair nodes are one overlap test and open their larger node); what differs between
// the paper's schedulers is only the order and who does the work:
//   sequential  one depth-first walk from the start node, one thread (ICCD);
//   phc         breadth-first from the start node until there are c · threads open nodes, then each of those is
//               a sub-task walked depth-first, taken by whichever thread is free first (dynamic, MCCD);
//   front       the BVTT front kept from the last step, cut into chunks of `chunk` nodes; a free thread takes
//               the next chunk and walks below each node of it (the paper's front decomposition).
// The parallel ones are re-enacted, not timed: every visit costs one unit, a thread takes its next task when its
// units are done, and the visits are listed in that simulated time (ties by thread), which is how they would
// interleave on threads of equal speed. Leaf pairs that overlap and are not adjacent are the candidates; every
// order finds the same ones.
#include <string>
#include <vector>

#include "framework/traversal/front/binary_front.hpp"
#include "framework/traversal/pass.hpp"

namespace ccdlab {

struct WalkVisit {
  Index a, b;          ///< the BVH nodes of the BVTT node
  bool tested = false;  ///< a pair node: one overlap test (a self node opens without one)
  bool overlap = false;
  bool candidate = false;  ///< two overlapping, non-adjacent leaves
  int task = -1;   ///< -1: the sequential walk or phc's breadth-first top; else the sub-task / chunk
  int thread = 0;
  long time = 0;   ///< the simulated unit at which the thread made this visit
};

struct BvttWalk {
  std::string scheduler;
  int threads = 1;
  int tasks = 0;
  std::vector<WalkVisit> visits;  ///< in visiting order
};

/// The walks from `start` (the pass's root pair by default, or a self node (n, n) to walk one sub-tree).
BvttWalk walk_sequential(const TraversalPass& pass, BvttNode start);
BvttWalk walk_phc(const TraversalPass& pass, BvttNode start, int threads, int tasks_per_thread);
/// The front's nodes under `start` (all of them for the root), in chunks.
BvttWalk walk_front(const TraversalPass& pass, BvttNode start, const std::vector<FrontNode>& front, int threads, int chunk);

}  // namespace ccdlab
