#include "framework/pipeline/memory_budget.hpp"

#include <algorithm>

#include "framework/hierarchy/bvh.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/narrow/representatives.hpp"
#include "framework/swept/end_boxes.hpp"
#include "framework/swept/feature_bounds.hpp"
#include "framework/swept/frame_points.hpp"
#include "framework/traversal/scheduler.hpp"
#include "framework/util/error.hpp"
#include "framework/util/memory.hpp"

namespace ccdlab {

MemoryPlan MemoryBudget::plan(std::uint64_t resident, std::size_t faces) const {
  MemoryPlan p;
  if (forced_slices_ > 0) return MemoryPlan{true, forced_slices_, 1, 0, 0, 0};
  // A step grows by a quarter over the last one at most, in the scenes we know; the first step is a guess.
  const auto grown = [](std::uint64_t last) { return last + last / 4; };
  p.expected_pairs = std::size_t(recorded_ ? grown(last_pairs_) : std::uint64_t(faces) * kFirstStepCandidatesPerFace);
  if (limit_ == 0) return p;
  if (resident >= limit_)
    fail("memory_limit {}: the mesh, BVH and per-step buffers already take {} resident before the traversal; raise "
         "memory_limit or lower the size of the scene", format_bytes(limit_), format_bytes(resident));
  p.budget_bytes = (limit_ - resident) / 2;  // half: the other half is the contacts' (TraversalDriver::run, StepWatch)
  const std::uint64_t estimated = std::uint64_t(std::min(estimate_, 1e15));  // pairs (1e15: no overflow below)
  p.predicted_bytes = std::max(estimated * kBytesPerCandidate,
                               last_transient_ > 0 ? grown(last_transient_)
                                                   : std::uint64_t(faces) * kFirstStepCandidatesPerFace * kBytesPerCandidate);
  if (p.predicted_bytes <= p.budget_bytes) return p;
  p.streamed = true;
  // Slices small enough that a few of them fill a flush: the buffer never overshoots by much.
  const std::uint64_t ratio = (p.predicted_bytes + p.budget_bytes - 1) / std::max<std::uint64_t>(p.budget_bytes, 1);
  p.slices = std::size_t(std::clamp<std::uint64_t>(16 * ratio, 16, 1u << 16));
  p.flush_pairs = std::max<std::size_t>(1, std::size_t(p.budget_bytes / kBytesPerCandidate / 2));
  return p;
}

bool MemoryBudget::fits(std::uint64_t resident, std::size_t faces) const {
  if (limit_ > 0 && resident >= limit_) return false;  // plan() would refuse the step
  return !plan(resident, faces).streamed;
}

void MemoryBudget::record(std::uint64_t candidate_pairs, std::uint64_t front_bytes) {
  last_transient_ = candidate_pairs * kBytesPerCandidate + front_bytes;
  last_pairs_ = candidate_pairs;
  recorded_ = true;
  estimate_ = 0;
}

std::uint64_t estimate_pipeline_bytes(const TriMesh& mesh, int k, int width, std::size_t orphan_pairs, bool end_boxes) {
  const std::uint64_t v = std::uint64_t(mesh.num_vertices()), e = std::uint64_t(mesh.num_edges()),
                      f = std::uint64_t(mesh.num_faces());
  const std::uint64_t bv = std::visit([](const auto& vec) { return std::uint64_t(sizeof(vec[0])); }, make_bvs(k));
  const std::uint64_t bvh = 2 * f * (sizeof(BvhNode) + sizeof(Index) + bv);  // nodes, leaf counts, node volumes
  const std::uint64_t wide_bounds =
      std::visit([](const auto& vec) { return std::uint64_t(sizeof(vec[0])); }, make_wide_bvs(k));
  // One wide node per inner node (f − 1) and the top one: its lanes, bounds and owner, plus a slot and a home per node.
  const std::uint64_t wide = width == 4 ? f * (sizeof(WideLayout::Lanes) + wide_bounds + sizeof(Index)) + 4 * f * sizeof(Index) : 0;
  const std::uint64_t feature_boxes = v * FeatureBounds::kBytesPerVertex;
  const std::uint64_t records = std::max<std::uint64_t>(f * sizeof(GatherRecord), kLargeAllocation);  // one huge page at least
  const std::uint64_t ownership = (v + e) * sizeof(Index) + f + records;  // owners, masks, the gather's records
  // The orphan set, and the same pairs again by the face that carries them (representatives.hpp), with a list
  // start and a signature per face.
  const std::uint64_t orphans = std::uint64_t(orphan_pairs) * (sizeof(EdgeEdgePair) + sizeof(CarriedOrphan)) +
                                f * (sizeof(std::uint32_t) + sizeof(std::uint64_t));
  // The frames, and stage 0's float copy with its faces' boxes (framework/swept/frame_points.hpp).
  const std::uint64_t frames = 2 * v * sizeof(Vec3) + v * sizeof(FloatFramePoints) + f * sizeof(FloatFaceBoxes);
  // End boxes: per node, and per wide node (framework/swept/end_boxes.hpp).
  const std::uint64_t ends = end_boxes ? 2 * f * sizeof(EndBoxes) + (width == 4 ? f * sizeof(WideEnds) : 0) : 0;
  return bvh + wide + feature_boxes + ownership + orphans + frames + ends;
}

}  // namespace ccdlab
