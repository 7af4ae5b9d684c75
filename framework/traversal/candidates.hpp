#pragma once
// What the broad phase hands to the narrow phase: candidate face pairs whose swept bounding volumes overlap.
#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "framework/mesh/tri_mesh.hpp"
#include "framework/util/parallel.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

struct FacePair {
  Index a;
  Index b;
  auto operator<=>(const FacePair&) const = default;
};

/// A list of candidates. Growing it leaves the new entries uninitialized (they are written right after).
using FacePairs = UninitializedVector<FacePair>;

/// Appends per-thread candidate lists to `out`, in list order (what a serial merge gives), copying in parallel
/// chunks; returns their trace (phase "merge_candidates"). Merged on one thread, n-body's 4.6M candidates
/// (37 MB written, its pages first touched by that thread) took ~25 ms of a ~110 ms traversal at two threads.
PhaseTrace append_candidates(FacePairs& out, std::span<const FacePairs* const> lists, int threads);

/// Work counters of a scheduler for one step (summed over passes).
struct TraversalStats {
  std::uint64_t bv_tests = 0;         ///< BV overlap tests performed
  std::uint64_t tasks = 0;            ///< parallel tasks (sub-trees, front chunks) handed out
  double serial_ms = 0;               ///< time in the scheduler's serial part (top of the BVTT, merging)
  // BVTT front (scheduler `front`)
  std::uint64_t front_nodes = 0;      ///< front size after the step
  std::uint64_t front_bytes = 0;      ///< memory of the front
  std::uint64_t front_visited = 0;    ///< front nodes processed this step
  std::uint64_t sprouted = 0;         ///< front nodes that overlapped and descended
  std::uint64_t pruned = 0;           ///< sibling pairs collapsed back into their parent
  std::uint64_t rebuilds = 0;         ///< fronts rebuilt from the root this step
  std::uint64_t cone_culled = 0;      ///< self tests skipped by normal-cone culling (topmost nodes)
  std::uint64_t contour_edges = 0;    ///< boundary edges tested by the contour test

  void add(const TraversalStats& o);
};

struct TraversalOutput {
  FacePairs pairs;
  std::uint64_t bv_tests = 0;  ///< BV overlap tests performed (kept beside stats for the sequential kernels)
  TraversalStats stats;

  void clear() {
    pairs.clear();
    bv_tests = 0;
    stats = {};
  }
};

}  // namespace ccdlab
