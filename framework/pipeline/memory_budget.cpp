#include "framework/pipeline/memory_budget.hpp"

#include <algorithm>

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
  p.budget_bytes = limit_ - resident;
  p.predicted_bytes = last_transient_ > 0 ? grown(last_transient_)
                                          : std::uint64_t(faces) * kFirstStepCandidatesPerFace * kBytesPerCandidate;
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
}

}  // namespace ccdlab
