#include "framework/traversal/candidates.hpp"

#include <algorithm>
#include <cstring>

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

PhaseTrace append_candidates(FacePairs& out, std::span<const FacePairs* const> lists, int threads) {
  PhaseTrace trace{"merge_candidates", Distribution::dynamic, 0, {}, {}};
  std::vector<std::size_t> offset(lists.size() + 1, out.size());
  for (std::size_t i = 0; i < lists.size(); ++i) offset[i + 1] = offset[i] + lists[i]->size();
  const std::size_t begin = out.size();
  out.resize(offset.back());
  // Chunks of the destination; a chunk copies from the one or more lists it overlaps.
  constexpr std::size_t kChunk = std::size_t(1) << 16;
  parallel_chunks(out.size() - begin, kChunk, threads, trace, [&](std::size_t b, std::size_t e, int) {
    b += begin;
    e += begin;
    for (std::size_t i = 0; i < lists.size(); ++i) {
      const std::size_t lo = std::max(b, offset[i]), hi = std::min(e, offset[i + 1]);
      if (lo < hi) std::memcpy(out.data() + lo, lists[i]->data() + (lo - offset[i]), (hi - lo) * sizeof(FacePair));
    }
  });
  return trace;
}

}  // namespace ccdlab
