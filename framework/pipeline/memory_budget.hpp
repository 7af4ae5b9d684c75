#pragma once
// The memory budget of one CCD step (config `memory_limit`). The persistent data (mesh, BVH, feature boxes,
// ownership, orphan set) is resident before the traversal starts; what a step adds on top — candidate face
// pairs, their thread-local copies, a BVTT front — grows with the contact density and is the paper's admitted
// memory risk. When the predicted transient memory does not fit under the limit, the step streams: each
// traversal pass is cut into BVTT slices, and the candidates are tested (and freed) whenever their buffer
// reaches the budget, so the transient part stays bounded whatever the scene does. Same contacts either way:
// the slices partition the BVTT, and contacts are sorted at the end of the step. The prediction counts every
// candidate as buffered, which only `sequential` does: the task schedulers hand their candidates to the narrow
// phase as they go (TraversalOutput::hand_over), so for them it is an upper bound.
#include <cstddef>
#include <cstdint>

#include "framework/mesh/tri_mesh.hpp"

namespace ccdlab {

struct MemoryPlan {
  bool streamed = false;
  std::size_t slices = 1;           ///< BVTT slices per traversal pass (1 = the whole pass at once)
  std::size_t flush_pairs = 0;      ///< test and free the candidates when this many are buffered (0 = never)
  std::uint64_t budget_bytes = 0;   ///< half of memory_limit − resident memory at the traversal's start (the other half: contacts)
  std::uint64_t predicted_bytes = 0;
  /// Candidate pairs the step is expected to find (the last step's plus a quarter, or the first-step guess):
  /// the room the candidate list reserves ahead when the step is not streamed.
  std::size_t expected_pairs = 0;
};

class MemoryBudget {
 public:
  /// Bytes one buffered candidate face pair costs: the pair in its thread's part of the list (CandidateList:
  /// the parts are read in place, never merged into a copy).
  static constexpr std::uint64_t kBytesPerCandidate = 8;
  /// Resident bytes per triangle of a whole run before its first traversal (mesh, frames, BVH, boxes, orphans),
  /// rounded down from the real steps' (docs/reliability.md). A lower bound for the refusal of a generated scene
  /// before it is made.
  static constexpr std::uint64_t kResidentBytesPerTriangle = 800;
  /// First-step guess of the candidates per triangle, before anything was measured: above the real cloth steps'.
  static constexpr std::uint64_t kFirstStepCandidatesPerFace = 64;

  /// `forced_slices` > 0: stream every step in that many slices per pass, flushing every slice.
  explicit MemoryBudget(std::uint64_t limit_bytes, std::size_t forced_slices = 0)
      : limit_(limit_bytes), forced_slices_(forced_slices) {}
  [[nodiscard]] std::uint64_t limit() const { return limit_; }

  /// The plan of a step over `faces` triangles whose traversal starts with `resident` bytes resident.
  /// Throws Error when the resident part alone is already above the limit.
  [[nodiscard]] MemoryPlan plan(std::uint64_t resident, std::size_t faces) const;
  /// Whether a step over `faces` triangles that starts with `resident` bytes resident runs unstreamed (always
  /// without a limit; never when streaming is forced). The pipeline asks it first with the last step's candidate
  /// pages still resident: a step that fits with them fits reusing them (at worst it adds to them what plan
  /// predicts); only one that does not frees them and plans from the resident memory without them.
  [[nodiscard]] bool fits(std::uint64_t resident, std::size_t faces) const;
  /// After a step: the transient bytes it would need unstreamed (candidates, front), for the next prediction.
  void record(std::uint64_t candidate_pairs, std::uint64_t front_bytes);
  /// The next step's candidates as estimated before its traversal (work_estimate.hpp): its plan predicts at least
  /// these (the first step's guess and the last step's count know nothing of a thickness that explodes the work).
  /// Used by the next plan only.
  void expect(double candidate_pairs) { estimate_ = candidate_pairs; }

 private:
  std::uint64_t limit_ = 0;  ///< 0 = no limit
  std::size_t forced_slices_ = 0;
  std::uint64_t last_transient_ = 0;
  std::uint64_t last_pairs_ = 0;
  bool recorded_ = false;
  double estimate_ = 0;  ///< expect()'s, for the next plan (0: none)
};

/// Bytes a pipeline over `mesh` will add before its first traversal: the BVHs and their volumes (the leaves' are
/// the faces' swept volumes; and their 4-wide view for width 4), the feature bounds, the ownership, the orphan set
/// and the two frames of a step. Checked against memory_limit when a pipeline is made, so that a run too large for
/// the machine is refused before it starts.
std::uint64_t estimate_pipeline_bytes(const TriMesh& mesh, int k, int width, std::size_t orphan_pairs,
                                      bool end_boxes = false);

}  // namespace ccdlab
