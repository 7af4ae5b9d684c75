// Real contact-heavy steps (../shared/data/meshes: rod-twist 3036 → 3037, n-body balls16 18 → 19; skipped where
// absent): `float` reports exactly the true contacts of the ground truth in every narrow mode and representative
// rule (one hash), and `conservative` misses none — at zero thickness, and at a separation η, where it must also
// find every pair `float` finds at η. (`exact` on these steps is left to `ccdlab step --tester exact`:
// minutes per step today; the funnel step checks it in test_funnel.cpp.)
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <optional>

#include "framework/mesh/mesh_io.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "support/ground_truth.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

struct RealStep {
  const char* scene;
  const char* t0;
  const char* t1;
  const char* truth_prefix;
};

struct Loaded {
  MeshData m0, m1;
  TriMesh mesh;
  test::GroundTruth truth;
};

std::optional<Loaded> load(const RealStep& s) {
  const std::string root = test::shared_data();
  const std::string dir = root + "/meshes/" + s.scene + "/";
  if (root.empty() || !std::filesystem::exists(dir + s.t0)) return std::nullopt;
  Loaded l{read_mesh(dir + s.t0), read_mesh(dir + s.t1), {}, {}};
  l.mesh = TriMesh(l.m0.positions.size(), l.m0.faces);
  l.truth = test::load_truth(root, s.scene, s.truth_prefix, l.mesh);
  return l;
}

StepResult run(const Loaded& l, const char* tester, NarrowOptions narrow, int threads = 2, double thickness = 0) {
  PipelineStrategies s;
  s.threads = threads;
  s.narrow = narrow;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({"phc", scheduler_registry().find("phc")->defaults()});
  ParamValues params = tester_registry().find(tester)->defaults();
  if (thickness > 0) params.set("thickness", thickness);
  s.tester = tester_registry().make({tester, params});
  CcdPipeline pipeline(l.mesh, single_cloth_body(l.mesh), std::move(s));
  return pipeline.step(l.m0.positions, l.m1.positions);
}

void split(const StepResult& r, std::set<VertexFacePair>& vf, std::set<EdgeEdgePair>& ee) {
  for (const Contact& c : r.contacts)
    if (c.kind == ContactKind::vf) vf.insert({c.feature_a, c.feature_b});
    else ee.insert({c.feature_a, c.feature_b});
}

class RealSteps : public ::testing::TestWithParam<RealStep> {};

TEST_P(RealSteps, FloatFindsExactlyTheTrueContactsInEveryNarrowMode) {
  const auto l = load(GetParam());
  if (!l) GTEST_SKIP() << GetParam().scene << " not found in ../shared/data/meshes: real-data test skipped";
  std::optional<std::uint64_t> hash;
  for (NarrowOptions o : {NarrowOptions{NarrowMode::batched, RepresentativeRule::fixed, {}},
                          NarrowOptions{NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::on}},
                          NarrowOptions{NarrowMode::batched, RepresentativeRule::first_free, {}},
                          NarrowOptions{NarrowMode::scalar, RepresentativeRule::fixed, {}}}) {
    const StepResult r = run(*l, "float", o);
    std::set<VertexFacePair> vf;
    std::set<EdgeEdgePair> ee;
    split(r, vf, ee);
    const std::string what = std::string(to_string(o.mode)) + "/" + std::string(to_string(o.representative)) +
                             (o.rules.orphan_carry == PassChoice::on ? " carrying the orphans" : "");
    EXPECT_EQ(vf, l->truth.vf_true) << what;
    EXPECT_EQ(ee, l->truth.ee_true) << what;
    const std::uint64_t h = contact_set_hash(r.contacts);
    if (!hash) hash = h;
    EXPECT_EQ(h, *hash) << what;
  }
}

TEST_P(RealSteps, ConservativeMissesNone) {
  const auto l = load(GetParam());
  if (!l) GTEST_SKIP() << GetParam().scene << " not found in ../shared/data/meshes: real-data test skipped";
  const StepResult r = run(*l, "conservative", {});
  std::set<VertexFacePair> vf;
  std::set<EdgeEdgePair> ee;
  split(r, vf, ee);
  for (const auto& p : l->truth.vf_true) EXPECT_TRUE(vf.count(p)) << "missed VF " << p.v << " " << p.f;
  for (const auto& p : l->truth.ee_true) EXPECT_TRUE(ee.count(p)) << "missed EE " << p.a << " " << p.b;
}

TEST_P(RealSteps, ConservativeWithASeparationFindsWhatExactAndFloatFind) {
  const auto l = load(GetParam());
  if (!l) GTEST_SKIP() << GetParam().scene << " not found in ../shared/data/meshes: real-data test skipped";
  constexpr double kEta = 1e-4;  // about 1/20 of an edge on these meshes
  std::set<VertexFacePair> vf, float_vf;
  std::set<EdgeEdgePair> ee, float_ee;
  split(run(*l, "conservative", {}, 2, kEta), vf, ee);
  split(run(*l, "float", {}, 2, kEta), float_vf, float_ee);
  for (const auto& p : l->truth.vf_true) EXPECT_TRUE(vf.count(p)) << "missed a true VF contact " << p.v << " " << p.f;
  for (const auto& p : l->truth.ee_true) EXPECT_TRUE(ee.count(p)) << "missed a true EE contact " << p.a << " " << p.b;
  for (const auto& p : float_vf) EXPECT_TRUE(vf.count(p)) << "missed float's VF pair " << p.v << " " << p.f;
  for (const auto& p : float_ee) EXPECT_TRUE(ee.count(p)) << "missed float's EE pair " << p.a << " " << p.b;
  std::cout << "[ " << GetParam().scene << " eta " << kEta << " ] conservative " << vf.size() << " VF + " << ee.size()
            << " EE, float " << float_vf.size() << " + " << float_ee.size() << ", true at 0: " << l->truth.vf_true.size()
            << " + " << l->truth.ee_true.size() << "\n";
}

INSTANTIATE_TEST_SUITE_P(Shared, RealSteps,
                         ::testing::Values(RealStep{"rod-twist", "3036.ply", "3037.ply", "3036"},
                                           RealStep{"n-body-simulation", "balls16_18.ply", "balls16_19.ply", "18"},
                                           RealStep{"cloth-funnel", "227.ply", "228.ply", "227"}),
                         [](const auto& info) {
                           std::string n = info.param.scene;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
}  // namespace ccdlab
