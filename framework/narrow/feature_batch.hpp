#pragma once
// A batch of feature pairs on its way through the narrow phase: gathered from candidate face pairs (or the
// orphan set), then compacted in place by each culling stage.
#include <cstdint>
#include <vector>

#include "framework/narrow/plane_filter.hpp"
#include "framework/narrow/window_distance_filter.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

struct FeatureBatch {
  UninitializedVector<VertexFacePair> vf;  // gather grows them by the most a chunk can append, then trims
  UninitializedVector<EdgeEdgePair> ee;
  /// Set when the gather ran stage 1 (coarse or float) already and counted the pairs (NarrowPhase::gather_orphans).
  bool coarse_done = false;
  /// After stage 3 (batched mode, testers with a cull reach): per pair, VF's then EE's, the start of its first
  /// open window. Before it the features were proven farther apart than the reach, so no contact the tester
  /// reports can happen earlier: a time reported below it (a lower bound, `conservative`) is raised to it, and
  /// the earliest-time query orders and cuts by it (earliest_cut.hpp). Empty otherwise (read as 0).
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
  WindowDistanceItems proximity;         ///< stage 4's (row, window) items
};

}  // namespace ccdlab
