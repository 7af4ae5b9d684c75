#pragma once
// Stage 1 of a step (design.md): the swept volumes. Every vertex's 26-DOP over the step (FeatureBounds) is
// computed once; the body hierarchies cut their leaves' k-DOPs from it (a face's volume is the union of its
// vertices', SweptFaceBv) and the narrow phase culls feature pairs with it (its stage 1). Neither owns it: the
// pipeline hands it to both.
#include "framework/mesh/tri_mesh.hpp"
#include "framework/hierarchy/end_boxes.hpp"
#include "framework/narrow/feature_bounds.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/scheduler.hpp"  // AnyBvs, AnyWideBvs
#include "framework/util/parallel.hpp"

namespace ccdlab {

/// The swept k-DOP of face f over the step: the union of its vertices' swept 26-DOPs, inflated by half the
/// thickness (FeatureBounds::face_dop: the one definition, shared with the narrow phase's stage 1).
template <class BV>
struct SweptFaceBv {
  const TriMesh& mesh;
  const FeatureBounds& bounds;
  BV operator()(Index f) const { return bounds.face_dop<BV::k>(mesh.face(f)); }
};

/// Faces per task wherever faces are swept or boxed: large enough to amortise a hand-out, small enough to balance.
inline constexpr std::size_t kFaceChunk = 2048;

/// An AnyBvs holding an empty vector of KDop<k>; throws Error unless is_kdop_k(k).
AnyBvs make_bvs(int k);
AnyWideBvs make_wide_bvs(int k);

/// Swept k-DOP of every face of the mesh over the step (inflated by thickness / 2), on `threads` threads; the
/// task costs go to `trace` when given. The pipeline writes these volumes into its BVH leaves instead; this
/// face-indexed array is for references (brute force) and benchmarks.
void compute_face_bvs(const TriMesh& mesh, const Positions& x_t0, const Positions& x_t1, double thickness, AnyBvs& out,
                      int threads = 1, PhaseTrace* trace = nullptr);

/// Every face's EndBoxes (framework/hierarchy/end_boxes.hpp), inflated as the pipeline inflates them for a tester
/// of reach `reach`: for references (brute force) and tests.
std::vector<EndBoxes> compute_face_end_boxes(const TriMesh& mesh, const Positions& x0, const Positions& x1,
                                             double thickness, const CullReach& reach);

}  // namespace ccdlab
