#include "framework/traversal/candidates.hpp"

namespace ccdlab {

void TraversalStats::add(const TraversalStats& o) {
  bv_tests += o.bv_tests;
  tasks += o.tasks;
  serial_ms += o.serial_ms;
  front_nodes += o.front_nodes;
  front_bytes += o.front_bytes;
  front_visited += o.front_visited;
  sprouted += o.sprouted;
  pruned += o.pruned;
  rebuilds += o.rebuilds;
  cone_culled += o.cone_culled;
  contour_edges += o.contour_edges;
}

}  // namespace ccdlab
