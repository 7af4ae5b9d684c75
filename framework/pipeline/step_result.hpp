#pragma once
// What one CCD step reports: the contacts, the work done (counters) and where the time went (phases).
#include <cstdint>
#include <vector>

#include "framework/narrow/narrow_counters.hpp"
#include "framework/primitive/contact.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

/// The step's work: the broad phase's counters here, the narrow phase's per stage (narrow_counters.hpp).
struct StepCounters : NarrowCounters {
  std::uint64_t bv_tests = 0;         ///< BVH node pair overlap tests in traversal
  std::uint64_t candidate_pairs = 0;  ///< non-adjacent face pairs whose swept BVs overlap
  std::uint64_t restructured = 0;     ///< BVH sub-trees rebuilt by adaptive restructuring
};

/// Wall-clock milliseconds per phase of one step (data flow of design.md).
struct StepTimings {
  double build_ms = 0;      ///< top-down BVH build: first step only, 0 afterwards
  double swept_bv_ms = 0;   ///< swept 26-DOP of every vertex (shared with the narrow phase), then every leaf's k-DOP
  double refit_ms = 0;      ///< bottom-up refit (and adaptive restructuring, when on)
  double cones_ms = 0;      ///< normal-cone culling: cones, contour tests (when on)
  double traverse_ms = 0;   ///< BVTT traversal → candidate face pairs
  double narrow_ms = 0;     ///< feature pairs of candidates → elementary tests
  double orphan_ms = 0;     ///< orphan set → elementary tests
  double total_ms = 0;      ///< all phases, build included
};

/// Resident memory of the step (framework/util/memory.hpp) and whether it had to stream to stay under the limit.
struct StepMemory {
  std::uint64_t peak_rss_bytes = 0;  ///< the process's peak resident memory during the step (0 = unknown)
  std::uint64_t limit_bytes = 0;     ///< memory_limit (0 = none)
  std::uint64_t slices = 0;          ///< BVTT slices per pass when streamed, 0 when not
  std::uint64_t page_faults = 0;     ///< minor page faults of the process during the step (new pages touched)
};

struct StepResult {
  Contacts contacts;  ///< sorted by feature identity
  StepCounters counters;
  StepTimings timings;
  TraversalStats traversal;        ///< the scheduler's counters (front size, serial time, …)
  StepMemory memory;
  std::vector<PhaseTrace> traces;  ///< per-phase task costs, for the schedule simulator
  /// Filled only when the pipeline records gathered feature pairs (tests of the representative rules).
  std::vector<VertexFacePair> tested_vf;
  std::vector<EdgeEdgePair> tested_ee;
};

}  // namespace ccdlab
