#pragma once
// Brute-force references for small meshes (O(n²)): the broad phase checks its candidates against every face
// pair, the whole pipeline its contacts against every feature pair (no BVH, no ownership, no culling).
#include <span>
#include <vector>

#include "framework/pipeline/bodies.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/swept/end_boxes.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

/// All face pairs (a < b) that may collide under `rules` and whose face BVs overlap, sorted; with `face_ends`
/// (one per face), only those not apart at both ends (framework/swept/end_boxes.hpp).
FacePairs brute_force_candidates(const TriMesh& mesh, const CollisionRules& rules, const AnyBvs& face_bvs,
                                 std::span<const EndBoxes> face_ends = {});

/// All colliding feature pairs: every VF (v ∉ f) and EE (no shared vertex) pair of interacting bodies,
/// each tested with `tester`. Sorted like CcdPipeline's contacts. With `box_cull`, pairs whose swept feature
/// 26-DOPs are not within η are skipped as the pipeline skips them (framework/swept/feature_bounds.hpp): the
/// reference for testers that may report a near miss as a hit (`float` within its tolerance), where the
/// question is only whether the BVH, the representative rule and the culling lost a pair.
Contacts brute_force_contacts(const TriMesh& mesh, const CollisionRules& rules, const Positions& x_t0,
                                          const Positions& x_t1, const PrimitiveTester& tester, bool box_cull = false);

/// Swept k-DOP of every face of the mesh over the step (inflated by thickness / 2), on `threads` threads; the
/// task costs go to `trace` when given. The pipeline writes these volumes into its BVH leaves instead; this
/// face-indexed array is for references and benchmarks.
void compute_face_bvs(const TriMesh& mesh, const Positions& x_t0, const Positions& x_t1, double thickness, AnyBvs& out,
                      int threads = 1, PhaseTrace* trace = nullptr);

/// Every face's EndBoxes, inflated as the pipeline inflates them for a tester of reach `reach`: for references
/// and tests.
std::vector<EndBoxes> compute_face_end_boxes(const TriMesh& mesh, const Positions& x0, const Positions& x1,
                                             double thickness, const CullReach& reach);

}  // namespace ccdlab
