// Real data: the UNC GAMMA cloth-funnel step 227 → 228 (../shared/data; skipped where absent). Its ground
// truth lists 134 colliding feature pairs (107 EE, 27 VF); the candidate feature pairs of our broad phase
// must include every one, for every K. The `float` tester's score is reported, not asserted (it is not
// conservative; the accuracy ladder measures it).
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <set>

#include <nlohmann/json.hpp>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "support/registries.hpp"
#include "support/ground_truth.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::GroundTruth;
GroundTruth load_truth(const std::string& root, const TriMesh& mesh) { return test::load_truth(root, "cloth-funnel", "227", mesh); }

TEST(FunnelStep, CandidatesIncludeAllCollidingPairsOfTheGroundTruth) {
  const std::string root = test::shared_data();
  if (root.empty() || !std::filesystem::exists(root + "/meshes/cloth-funnel/227.ply"))
    GTEST_SKIP() << "../shared/data/meshes/cloth-funnel not found: real-data test skipped";
  MeshData m0 = read_mesh(root + "/meshes/cloth-funnel/227.ply");
  MeshData m1 = read_mesh(root + "/meshes/cloth-funnel/228.ply");
  ASSERT_EQ(m0.faces, m1.faces);
  TriMesh mesh(Index(m0.positions.size()), m0.faces);
  ASSERT_EQ(mesh.num_vertices(), 9450);
  ASSERT_EQ(mesh.num_faces(), 18484);
  EXPECT_EQ(mesh.num_components(), 4);
  GroundTruth gt = load_truth(root, mesh);
  ASSERT_EQ(gt.vf_true.size(), 27u);
  ASSERT_EQ(gt.ee_true.size(), 107u);

  for (int k : test::kdop_ks()) {
    PipelineStrategies s;
    s.k = k;
    s.builder = builder_registry().make({"median", {}});
    s.scheduler = scheduler_registry().make({"sequential", {}});
    s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
    CcdPipeline pipeline(mesh, single_cloth_body(mesh), std::move(s));
    pipeline.set_record_tested_pairs(true);
    StepResult r = pipeline.step(m0.positions, m1.positions);
    std::set<VertexFacePair> tested_vf(r.tested_vf.begin(), r.tested_vf.end());
    std::set<EdgeEdgePair> tested_ee(r.tested_ee.begin(), r.tested_ee.end());
    for (const auto& p : gt.vf_true) EXPECT_TRUE(tested_vf.count(p)) << "K=" << k << " lost VF " << p.v << " " << p.f;
    for (const auto& p : gt.ee_true) EXPECT_TRUE(tested_ee.count(p)) << "K=" << k << " lost EE " << p.a << " " << p.b;

    int found_vf = 0, found_ee = 0, false_vf = 0, false_ee = 0, outside = 0;
    for (const Contact& c : r.contacts) {
      if (c.kind == ContactKind::vf) {
        VertexFacePair p{c.feature_a, c.feature_b};
        found_vf += gt.vf_true.count(p) > 0;
        false_vf += gt.vf_false.count(p) > 0;
        outside += !gt.vf_true.count(p) && !gt.vf_false.count(p);
      } else {
        EdgeEdgePair p{c.feature_a, c.feature_b};
        found_ee += gt.ee_true.count(p) > 0;
        false_ee += gt.ee_false.count(p) > 0;
        outside += !gt.ee_true.count(p) && !gt.ee_false.count(p);
      }
    }
    std::cout << "[funnel K=" << k << "] float tester: " << found_vf << "/27 VF and " << found_ee
              << "/107 EE true contacts found; false positives " << false_vf << " VF, " << false_ee
              << " EE; contacts outside the upstream list " << outside << "; candidate feature pairs "
              << r.tested_vf.size() << " VF, " << r.tested_ee.size() << " EE\n";
    RecordProperty("float_found_k" + std::to_string(k), found_vf + found_ee);
    // Every K yields the same contact set (the BV only changes the culling).
    static std::uint64_t first_hash = 0;
    if (k == 6) first_hash = contact_set_hash(r.contacts);
    EXPECT_EQ(contact_set_hash(r.contacts), first_hash) << "K=" << k;
  }
}

TEST(FunnelStep, ConservativeAndExactPipelinesFindExactlyTheGroundTruth) {
  // The whole pipeline with the two testers that claim correctness: the contact set must be exactly the 134
  // colliding pairs of the upstream list — nothing missed, nothing more.
  const std::string root = test::shared_data();
  if (root.empty() || !std::filesystem::exists(root + "/meshes/cloth-funnel/227.ply"))
    GTEST_SKIP() << "../shared/data/meshes/cloth-funnel not found: real-data test skipped";
  MeshData m0 = read_mesh(root + "/meshes/cloth-funnel/227.ply");
  MeshData m1 = read_mesh(root + "/meshes/cloth-funnel/228.ply");
  TriMesh mesh(Index(m0.positions.size()), m0.faces);
  GroundTruth gt = load_truth(root, mesh);
  for (const char* tester : {"conservative", "exact"}) {
    PipelineStrategies s;
    s.builder = builder_registry().make({"median", {}});
    s.scheduler = scheduler_registry().make({"sequential", {}});
    s.tester = tester_registry().make({tester, tester_registry().find(tester)->defaults()});
    CcdPipeline pipeline(mesh, single_cloth_body(mesh), std::move(s));
    StepResult r = pipeline.step(m0.positions, m1.positions);
    std::set<VertexFacePair> vf;
    std::set<EdgeEdgePair> ee;
    for (const Contact& c : r.contacts)
      if (c.kind == ContactKind::vf) vf.insert({c.feature_a, c.feature_b});
      else ee.insert({c.feature_a, c.feature_b});
    EXPECT_EQ(vf, gt.vf_true) << tester;
    EXPECT_EQ(ee, gt.ee_true) << tester;
  }
}

}  // namespace
}  // namespace ccdlab
