#pragma once
// The narrow phase of one step: turns feature pairs into elementary tests and contacts.
// Before each elementary test, the swept axis-aligned boxes of the two features (vertex: 2 points, edge: 4,
// face: 6; inflated by η) are compared; min/max of doubles are exact, so this cull never loses a contact.
#include <vector>

#include "framework/pipeline/step_result.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

class NarrowPhase {
 public:
  NarrowPhase(const TriMesh& mesh, const Ownership& owners, const PrimitiveTester& tester)
      : mesh_(mesh), owners_(owners), tester_(tester) {}

  /// Sets the two frames of the step and computes the swept box of every vertex, edge and face.
  void begin_step(const Positions& x_t0, const Positions& x_t1, int threads = 1, PhaseTrace* trace = nullptr);

  /// One VF feature pair (v ∉ f): box cull, then the elementary test; appends a contact on hit.
  void test_vf(Index v, Index f, std::vector<Contact>& out, StepCounters& c, bool box_cull = true) const;
  /// One EE feature pair (no shared vertex).
  void test_ee(Index a, Index b, std::vector<Contact>& out, StepCounters& c, bool box_cull = true) const;
  /// The feature pairs of a non-adjacent candidate face pair under the ownership rule (feature_pairs.hpp).
  /// When `record` is given, appends the pairs considered (for tests of the ownership rule).
  void test_face_pair(Index fa, Index fb, std::vector<Contact>& out, StepCounters& c, StepResult* record = nullptr) const;

  [[nodiscard]] VertexFaceQuery vf_query(Index v, Index f) const;
  [[nodiscard]] EdgeEdgeQuery ee_query(Index a, Index b) const;

 private:

  const TriMesh& mesh_;
  const Ownership& owners_;
  const PrimitiveTester& tester_;
  const Positions* x_t0_ = nullptr;
  const Positions* x_t1_ = nullptr;
  // Swept boxes of every vertex, edge and face over the step; the face and edge boxes are inflated by η so
  // each cull is a single overlap test.
  std::vector<Box3> vertex_box_;
  std::vector<Box3> edge_box_;
  std::vector<Box3> face_box_;
};

}  // namespace ccdlab
