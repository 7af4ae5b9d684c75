// Normal-cone culling must never change the contacts: against brute force on crumpled meshes, against no
// culling on the folding scene for every scheduler and thread count, and on adversarial cases.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "strategies/scenes/drape_fold_scene.hpp"
#include "framework/util/error.hpp"
#include "support/registries.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

PipelineStrategies with_cones(const std::string& scheduler, int threads, bool cones, int k = 18) {
  PipelineStrategies s;
  s.k = k;
  s.threads = threads;
  s.normal_cones = cones;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({scheduler, scheduler_registry().find(scheduler)->defaults()});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  return s;
}

std::vector<std::tuple<ContactKind, Index, Index>> keys(const Contacts& cs) {
  std::vector<std::tuple<ContactKind, Index, Index>> k;
  for (const Contact& c : cs) k.push_back(c.key());
  return k;
}

TEST(NormalCones, FlatSheetIsCulledWhole) {
  MeshData g = test::grid(16, 16);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  CcdPipeline p(mesh, single_cloth_body(mesh), with_cones("sequential", 1, true));
  Positions x1 = g.positions;
  for (Vec3& x : x1) x += Vec3(0.1, 0.05, 0.02);  // rigid translation: the sheet stays a height field
  StepResult r = p.step(g.positions, x1);
  EXPECT_EQ(r.traversal.cone_culled, 1u) << "the root patch is a disk with one normal: its self test is skipped";
  EXPECT_EQ(r.counters.candidate_pairs, 0u);
  EXPECT_TRUE(r.contacts.empty());
}

TEST(NormalCones, StackedSheetsAreNotOneDiskAndStillCollide) {
  // Two parallel sheets in one body: same normals, but two boundary loops — no cull at their common ancestors.
  MeshData two = test::concat(test::grid(8, 8), test::grid(8, 8));
  const std::size_t half = two.positions.size() / 2;
  Positions x0 = two.positions, x1 = two.positions;
  for (std::size_t v = half; v < x0.size(); ++v) x0[v].z() = 0.05, x1[v].z() = -0.05;  // passes through
  TriMesh mesh(Index(two.positions.size()), two.faces);
  CcdPipeline culled(mesh, single_cloth_body(mesh), with_cones("front", 2, true));
  CollisionRules rules(mesh, single_cloth_body(mesh));
  StepResult r = culled.step(x0, x1);
  auto truth = brute_force_contacts(mesh, rules, x0, x1, *culled.strategies().tester);
  ASSERT_GT(truth.size(), 50u);
  EXPECT_EQ(keys(r.contacts), keys(truth));
}

TEST(NormalCones, CrumpledMeshesMatchBruteForce) {
  MeshData g = test::grid(10, 9);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::size_t total = 0, culled_nodes = 0;
  for (int k : {6, 18}) {
    CcdPipeline p(mesh, single_cloth_body(mesh), with_cones("sequential", 1, true, k));
    for (unsigned seed = 1; seed <= 6; ++seed) {
      std::mt19937 rng(seed);
      // Mildly crumpled, small motion: some patches stay height fields (culled), some fold (not).
      Positions x0 = test::crumple(g.positions, rng, 0.002);
      Positions x1 = x0;
      std::uniform_real_distribution<double> u(-1, 1);
      for (Vec3& x : x1) x += 0.03 * Vec3(u(rng), u(rng), u(rng));
      StepResult r = p.step(x0, x1);
      auto truth = brute_force_contacts(mesh, p.rules(), x0, x1, *p.strategies().tester);
      EXPECT_EQ(keys(r.contacts), keys(truth)) << "k " << k << " seed " << seed;
      total += truth.size();
      culled_nodes += r.traversal.cone_culled;
    }
  }
  EXPECT_GT(total, 20u);
  EXPECT_GT(culled_nodes, 0u) << "the test must exercise culling";
}

TEST(NormalCones, FoldingSceneSameContactsForEverySchedulerAndThreadCount) {
  DrapeFoldParams dp;
  dp.resolution = 24;
  dp.frames = 10;
  dp.sphere_segments = 12;
  const MeshSequence scene = make_drape_fold_scene(dp);
  auto hashes = [&](PipelineStrategies s, std::uint64_t* culled = nullptr) {
    CcdPipeline p(scene.topology(), scene.bodies(), std::move(s));
    std::vector<std::uint64_t> h;
    Positions x0 = scene.frame(0);
    for (int i = 0; i < scene.num_steps(); ++i) {
      Positions x1 = scene.frame(i + 1);
      StepResult r = p.step(x0, x1);
      h.push_back(contact_set_hash(r.contacts));
      if (culled) *culled += r.traversal.cone_culled;
      x0 = std::move(x1);
    }
    return h;
  };
  const auto reference = hashes(with_cones("sequential", 1, false));
  std::uint64_t culled = 0;
  for (const std::string& s : test::bvtt_schedulers())
    for (int threads : {1, 2, 4}) EXPECT_EQ(hashes(with_cones(s, threads, true), &culled), reference) << s << " x" << threads;
  EXPECT_GT(culled, 0u);
}

TEST(NormalCones, RefusedWithThickness) {
  MeshData g = test::grid(4, 4);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  PipelineStrategies s = with_cones("sequential", 1, true);
  s.tester = tester_registry().make({"float", [] {
                                       ParamValues v;
                                       v.set("thickness", 0.01);
                                       return v;
                                     }()});
  EXPECT_THROW(CcdPipeline(mesh, single_cloth_body(mesh), std::move(s)), Error);
}

}  // namespace
}  // namespace ccdlab
