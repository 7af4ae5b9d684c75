// A step whose work explodes is refused before its traversal (work_estimate.hpp, candidate_limit): the estimate
// is n(n − 1)/2 when every swept volume holds the scene, close to the traversal's count on an ordinary step, and
// the refusal names the estimate, the limit and the cause (the thickness against the scene's size, or the
// motion); with the limit off, or above the estimate, the step runs.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/pipeline/work_estimate.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "support/error_of.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

PipelineStrategies strategies(double thickness, double candidate_limit) {
  PipelineStrategies s = contact_strategies(18, "sequential", 1, 0.0);
  ParamValues params = tester_registry().find("float")->defaults();
  params.set("thickness", thickness);
  s.tester = tester_registry().make({"float", params});
  s.candidate_limit = candidate_limit;
  return s;
}

/// The message of the Error a step throws; empty when it throws none.
std::string error_of(CcdPipeline& p, const Positions& x0, const Positions& x1) {
  return test::error_of([&] { (void)p.step(x0, x1); });
}

/// A sheet crumpled in its first frame, each vertex moved by up to a tenth of an edge in its second.
struct Sheet {
  MeshData grid;
  TriMesh mesh;
  Positions x0, x1;
  explicit Sheet(int n) : grid(test::grid(n, n)), mesh(Index(grid.positions.size()), grid.faces) {
    std::mt19937 rng(5);
    x0 = test::crumple(grid.positions, rng, 0.01);
    std::uniform_real_distribution<double> jitter(-0.1, 0.1);
    const double edge = (grid.positions[1] - grid.positions[0]).norm();
    x1 = x0;
    for (Vec3& x : x1) x += edge * Vec3(jitter(rng), jitter(rng), jitter(rng));
  }
};

TEST(WorkEstimate, IsEveryPairWhenEachSweptVolumeHoldsTheScene) {
  const Sheet s(12);  // 242 triangles
  CcdPipeline p(s.mesh, single_cloth_body(s.mesh), strategies(10.0, 0));  // thickness 10 × the sheet's size
  (void)p.step(s.x0, s.x1);
  const double n = double(s.mesh.num_faces());
  const WorkEstimate e = estimate_candidates(p.passes(), s.mesh.num_faces());
  EXPECT_EQ(e.sampled, kWorkEstimateSamples);
  EXPECT_NEAR(e.candidates, n * (n - 1) / 2, 1e-9 * n * n);
}

TEST(WorkEstimate, IsNearTheTraversalsCountOnAnOrdinaryStep) {
  const Sheet s(32);
  CcdPipeline p(s.mesh, single_cloth_body(s.mesh), strategies(0.0, PipelineSettings{}.candidate_limit));
  const StepResult r = p.step(s.x0, s.x1);
  const WorkEstimate e = estimate_candidates(p.passes(), s.mesh.num_faces());
  // The estimate counts the adjacent pairs too (up to 6 per face more), which the traversal leaves out.
  EXPECT_GE(e.candidates, 0.5 * double(r.counters.candidate_pairs));
  EXPECT_LE(e.per_face(), double(r.counters.candidate_pairs) / double(s.mesh.num_faces()) * 2 + 7);
  EXPECT_LT(e.per_face(), 30);
}

TEST(WorkEstimate, AThicknessInTheWrongUnitIsRefusedWithTheNumbers) {
  const Sheet s(12);  // 242 triangles: ~120 candidates per triangle when every pair is one
  CcdPipeline p(s.mesh, single_cloth_body(s.mesh), strategies(10.0, 100));
  const std::string message = error_of(p, s.x0, s.x1);
  EXPECT_NE(message.find("candidate triangle pairs expected"), std::string::npos) << message;
  EXPECT_NE(message.find("above candidate_limit = 100 per triangle"), std::string::npos) << message;
  EXPECT_NE(message.find("thickness 10 is"), std::string::npos) << message;
  EXPECT_NE(message.find("mean edge length"), std::string::npos) << message;
  // Without the limit, or with one above the estimate, the same step runs.
  for (const double limit : {0.0, 200.0}) {
    CcdPipeline q(s.mesh, single_cloth_body(s.mesh), strategies(10.0, limit));
    EXPECT_EQ(error_of(q, s.x0, s.x1), "no error") << limit;
  }
}

TEST(WorkEstimate, FramesOfDifferentScalesAreRefusedByTheirMotion) {
  const Sheet s(32);
  Positions far = s.x0;
  for (Vec3& x : far) x *= 1000.0;  // the second frame in millimetres
  CcdPipeline p(s.mesh, single_cloth_body(s.mesh), strategies(0.0, 100));
  const std::string message = error_of(p, s.x0, far);
  EXPECT_NE(message.find("above candidate_limit = 100 per triangle"), std::string::npos) << message;
  EXPECT_NE(message.find("largest vertex motion"), std::string::npos) << message;
  // A later step whose scene has grown past twice its size is estimated again.
  CcdPipeline q(s.mesh, single_cloth_body(s.mesh), strategies(0.0, 100));
  EXPECT_EQ(error_of(q, s.x0, s.x1), "no error");
  EXPECT_NE(error_of(q, s.x1, far).find("largest vertex motion"), std::string::npos);
}

TEST(WorkEstimate, TheLimitIsChecked) {
  PipelineSettings settings;
  settings.candidate_limit = -1;
  EXPECT_THROW(settings.validate(), Error);
  settings.candidate_limit = std::numeric_limits<double>::infinity();
  EXPECT_THROW(settings.validate(), Error);
  settings.candidate_limit = 0;
  EXPECT_NO_THROW(settings.validate());
}

}  // namespace
}  // namespace ccdlab
