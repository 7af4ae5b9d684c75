#pragma once
// The work of a step, estimated before its traversal runs, so that an input whose work explodes — a thickness in
// the wrong unit, a scene scaled by 1000 against an absolute thickness, a frame that throws the mesh across the
// scene — is refused in seconds with the numbers that explain it, instead of running for minutes and growing
// until the machine kills it. The candidates cannot be streamed away: each of them becomes feature pairs and,
// at such a thickness, contacts, which are the step's answer.
//
// The estimate: a fixed sample of faces (evenly spaced over each pass's first side), each face's swept volume —
// its leaf's, as refit for this step — tested against the other side's hierarchy, the overlapping leaves
// counted (a whole sub-tree at once where the volume contains the node's). Cost: a few hundred descents, each
// O(log n + its count); a sub-tree inside the volume is not opened, so even the quadratic case stays cheap.
#include <cstddef>
#include <string>
#include <vector>

#include "framework/mesh/tri_mesh.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

struct WorkEstimate {
  double candidates = 0;    ///< expected candidate face pairs of the step (all passes; self pairs once)
  std::size_t faces = 0;    ///< triangles of the mesh
  std::size_t sampled = 0;  ///< faces whose overlaps were counted
  [[nodiscard]] double per_face() const { return faces == 0 ? 0.0 : candidates / double(faces); }
};

/// Faces sampled per pass side (all of them when the side has fewer).
inline constexpr std::size_t kWorkEstimateSamples = 256;

/// The estimate over the passes' refit hierarchies (binary node volumes), `faces` triangles in the mesh.
[[nodiscard]] WorkEstimate estimate_candidates(const std::vector<TraversalPass>& passes, std::size_t faces,
                                               std::size_t samples = kWorkEstimateSamples);

/// The coordinates the pipeline computes reliably: |x| up to kMaxCoordinate (its bounding volumes are single
/// precision, and the float tester's cubic multiplies three coordinates), and a scene whose bounding-box diagonal
/// is 0 or at least kMinDiagonal (the float tester's tolerances multiply three lengths: below, they underflow
/// and its answers are wrong). Between them lie 60 orders of magnitude: scenes scaled by 1e±6 answer as unscaled.
inline constexpr double kMaxCoordinate = 1e30, kMinDiagonal = 1e-30;

/// The bounding-box diagonal of one frame (0 when empty; no underflow for tiny scenes): what a relative d̂ or
/// thickness is a fraction of.
[[nodiscard]] double bounding_box_diagonal(const Positions& x);

/// Empty when the frames lie within those bounds; else what is wrong, as a sentence for a refusal.
[[nodiscard]] std::string scale_problem(const Positions& x_t0, const Positions& x_t1);

/// Why a step over these frames would have `estimate`'s work: the tester's thickness against the scene's
/// bounding-box diagonal and the mesh's mean edge length (at x_t0), or, where the thickness is small, the
/// largest vertex motion of the step. One or two sentences, ending in their punctuation, for the refusal's message.
/// `thickness_name` says what the thickness is to the user (PrimitiveTester::thickness_name).
[[nodiscard]] std::string explain_work(const TriMesh& mesh, const Positions& x_t0, const Positions& x_t1, double thickness,
                                       std::string_view thickness_name = "the tester's thickness");

}  // namespace ccdlab
