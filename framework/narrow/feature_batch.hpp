#pragma once
// A batch of feature pairs on its way through the narrow phase: gathered from candidate face pairs (or the
// orphan set), then compacted in place by each culling stage.
#include <cstdint>
#include <vector>

#include "framework/narrow/plane_filter.hpp"
#include "framework/narrow/proximity_filter.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

struct FeatureBatch {
  UninitializedVector<VertexFacePair> vf;  // gather grows them by the most a chunk can append, then trims
  UninitializedVector<EdgeEdgePair> ee;
  /// Set when the gather ran stage 1's coarse test already and counted the pairs (NarrowPhase::gather_orphans).
  bool coarse_done = false;
  /// Only for the earliest-time query (earliest_cut.hpp), after stage 3: per pair, VF's then EE's, the start of
  /// its first open window, before which the tester cannot report it. Empty otherwise (read as 0).
  std::vector<float> from;
  void clear() {
    vf.clear();
    ee.clear();
    from.clear();
    coarse_done = false;
  }
};

/// Per-thread working memory of the narrow phase, reused from chunk to chunk (no allocation in steady state).
struct NarrowScratch {
  UninitializedVector<FacePair> candidates;  ///< stage 0's survivors, gathered from
  FeatureBatch batch;
  PlaneBatch plane;
  std::vector<std::uint8_t> keep;
  std::vector<std::uint16_t> open;  ///< stage 3's open windows per row, for stage 4
  ProximityItems proximity;         ///< stage 4's (row, window) items
};

}  // namespace ccdlab
