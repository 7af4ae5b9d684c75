// Differential tests: the BVH pipeline against brute force on random deforming meshes, for every K and both
// builders — candidate face pairs (broad phase) and contacts (whole pipeline) must be identical sets.
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <random>

#include "framework/pipeline/brute_force.hpp"
#include "framework/util/simd_target.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

struct Case {
  int k;
  std::string builder;
  int width = 2;  ///< bv.width: the binary BVTT or the 4-wide view (same candidates)
  /// CCDLAB_SIMD for the case, or "" for the CPU's best: "avx2" makes width 4 take the AVX2 lane-pair walk, "sse4"
  /// the SSE2 walk (traverse_bvtt_wide), instead of the AVX-512 one on a CPU that has AVX-512.
  std::string simd = "";
};

PipelineStrategies strategies(const Case& c) {
  PipelineStrategies s;
  s.k = c.k;
  s.width = c.width;
  s.builder = builder_registry().make({c.builder, builder_registry().find(c.builder)->defaults()});
  s.scheduler = scheduler_registry().make({"sequential", {}});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  return s;
}

/// A crumpled sheet moving by a smooth motion plus per-vertex noise: many self-contacts.
struct Frames {
  Positions x0, x1;
};
Frames random_step(const Positions& rest, unsigned seed, double motion) {
  std::mt19937 rng(seed);
  Frames f;
  f.x0 = test::crumple(rest, rng, 0.02);
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3 drift(u(rng), u(rng), u(rng));
  f.x1 = f.x0;
  for (Vec3& p : f.x1) p += motion * (0.5 * drift + Vec3(u(rng), u(rng), u(rng)));
  return f;
}

/// The faces' swept volumes as the pipeline's leaves hold them (same k, same thickness), indexed by face.
AnyBvs swept_face_bvs(const CcdPipeline& pipeline, const Positions& x0, const Positions& x1) {
  AnyBvs bvs = make_bvs(pipeline.strategies().k);
  compute_face_bvs(pipeline.mesh(), x0, x1, pipeline.strategies().tester->thickness(), bvs);
  return bvs;
}

/// The brute-force candidates the pipeline must find: the pairs of overlapping face volumes, less those whose end
/// boxes are apart at both ends when the pipeline tests them.
FacePairs reference_candidates(const CcdPipeline& pipeline, const Positions& x0, const Positions& x1) {
  const PrimitiveTester& tester = *pipeline.strategies().tester;
  std::vector<EndBoxes> ends;
  if (pipeline.end_boxes_in_last_step()) ends = compute_face_end_boxes(pipeline.mesh(), x0, x1, tester.thickness(), *tester.cull_reach());
  return brute_force_candidates(pipeline.mesh(), pipeline.rules(), swept_face_bvs(pipeline, x0, x1), ends);
}

std::vector<std::tuple<ContactKind, Index, Index>> keys(const Contacts& cs) {
  std::vector<std::tuple<ContactKind, Index, Index>> k;
  for (const Contact& c : cs) k.push_back(c.key());
  return k;
}

class Differential : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    if (!GetParam().simd.empty() && (hwy::SupportedTargets() & HWY_AVX2)) limit_simd_target(GetParam().simd);
  }
  void TearDown() override { hwy::SetSupportedTargetsForTest(0); }
};

TEST_P(Differential, SelfCollisionMatchesBruteForce) {
  MeshData g = test::grid(9, 7);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies(GetParam()));
  pipeline.keep_candidates(true);
  std::size_t total_contacts = 0;
  StepResult r;  // reused by every step (its contact list's memory): nothing of one step may leak into the next
  for (unsigned seed = 1; seed <= 4; ++seed) {
    Frames f = random_step(g.positions, seed, 0.05);
    pipeline.step(f.x0, f.x1, r);
    auto candidates = pipeline.last_candidates().pairs.flatten();
    std::sort(candidates.begin(), candidates.end());
    EXPECT_EQ(std::adjacent_find(candidates.begin(), candidates.end()), candidates.end()) << "duplicate candidate";
    EXPECT_EQ(candidates, reference_candidates(pipeline, f.x0, f.x1)) << "seed " << seed;
    auto expected = brute_force_contacts(mesh, pipeline.rules(), f.x0, f.x1, *pipeline.strategies().tester);
    EXPECT_EQ(keys(r.contacts), keys(expected)) << "seed " << seed;
    EXPECT_EQ(r.counters.contacts_vf + r.counters.contacts_ee, r.contacts.size());
    total_contacts += r.contacts.size();
  }
  EXPECT_GT(total_contacts, 20u) << "the random steps must actually collide, or the test proves nothing";
}

TEST_P(Differential, ClothAgainstObstacleMatchesBruteForce) {
  // A cloth (self-collision off) falling through a still obstacle sheet below it.
  MeshData cloth = test::grid(6, 6), obstacle = test::grid(5, 4);
  for (Vec3& p : obstacle.positions) p = Vec3(p.x() * 1.2 - 0.1, p.y() * 1.2 - 0.1, -0.05 + 0.02 * std::sin(7 * p.x()));
  MeshData both = test::concat(cloth, obstacle);
  TriMesh mesh(Index(both.positions.size()), both.faces);
  const Index nv = Index(cloth.positions.size()), nf = Index(cloth.faces.size());
  std::vector<Body> bodies{{"cloth", BodyKind::cloth, false, 0, nv, 0, nf},
                           {"obstacle", BodyKind::obstacle, false, nv, mesh.num_vertices(), nf, mesh.num_faces()}};
  CcdPipeline pipeline(mesh, bodies, strategies(GetParam()));
  pipeline.keep_candidates(true);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  Positions x0 = both.positions, x1 = both.positions;
  for (Index v = 0; v < nv; ++v) {
    x0[v] += Vec3(0, 0, 0.05 + 0.01 * u(rng));
    x1[v] += Vec3(0.02 * u(rng), 0.02 * u(rng), -0.1 + 0.03 * u(rng));
  }
  StepResult r = pipeline.step(x0, x1);
  auto candidates = pipeline.last_candidates().pairs.flatten();
  std::sort(candidates.begin(), candidates.end());
  EXPECT_EQ(candidates, reference_candidates(pipeline, x0, x1));
  auto expected = brute_force_contacts(mesh, pipeline.rules(), x0, x1, *pipeline.strategies().tester);
  EXPECT_EQ(keys(r.contacts), keys(expected));
  EXPECT_GT(r.contacts.size(), 10u);
  EXPECT_EQ(r.counters.orphan_vf + r.counters.orphan_ee, 0u) << "no self-collision: no orphan set";
  for (const Contact& c : r.contacts) {
    // Every contact joins the two bodies.
    bool a_cloth = c.vertices[0] < nv, b_cloth = c.vertices[c.kind == ContactKind::vf ? 1 : 2] < nv;
    EXPECT_NE(a_cloth, b_cloth);
  }
}

TEST_P(Differential, EndBoxesDropOnlyPairsApartAtBothEndsAndNoContact) {
  // The same steps with end boxes on and off (framework/swept/end_boxes.hpp): off, the candidates are exactly
  // the overlapping face volumes; on, those less the pairs apart at both ends — some every step, since the
  // random motion moves faces across one another's boxes — and the contacts are the same.
  MeshData g = test::grid(9, 7);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  PipelineStrategies on = strategies(GetParam()), off = strategies(GetParam());
  on.end_boxes = EndBoxMode::on, off.end_boxes = EndBoxMode::off;
  CcdPipeline with(mesh, single_cloth_body(mesh), std::move(on)), without(mesh, single_cloth_body(mesh), std::move(off));
  ASSERT_TRUE(with.end_boxes_kept());
  ASSERT_FALSE(without.end_boxes_kept());
  with.keep_candidates(true), without.keep_candidates(true);
  for (unsigned seed = 1; seed <= 4; ++seed) {
    Frames f = random_step(g.positions, seed, 0.05);
    const StepResult a = with.step(f.x0, f.x1), b = without.step(f.x0, f.x1);
    auto kept = with.last_candidates().pairs.flatten(), all = without.last_candidates().pairs.flatten();
    std::sort(kept.begin(), kept.end()), std::sort(all.begin(), all.end());
    EXPECT_EQ(all, brute_force_candidates(mesh, without.rules(), swept_face_bvs(without, f.x0, f.x1))) << "seed " << seed;
    EXPECT_TRUE(std::includes(all.begin(), all.end(), kept.begin(), kept.end())) << "seed " << seed;
    EXPECT_LT(kept.size(), all.size()) << "seed " << seed << ": the end boxes dropped nothing";
    EXPECT_EQ(keys(a.contacts), keys(b.contacts)) << "seed " << seed;
    EXPECT_LT(a.counters.bv_tests, b.counters.bv_tests) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryKAndBuilder, Differential,
                         ::testing::Values(Case{6, "median"}, Case{14, "median"}, Case{18, "median"}, Case{26, "median"},
                                           Case{6, "sah"}, Case{14, "sah"}, Case{18, "sah"}, Case{26, "sah"},
                                           Case{6, "median", 4}, Case{14, "sah", 4}, Case{18, "median", 4},
                                           Case{26, "sah", 4}, Case{6, "sah", 4, "avx2"}, Case{18, "median", 4, "avx2"},
                                           Case{26, "median", 4, "avx2"}, Case{6, "sah", 4, "sse4"},
                                           Case{18, "median", 4, "sse4"}, Case{26, "median", 4, "sse4"}),
                         [](const auto& info) {
                           return info.param.builder + "_k" + std::to_string(info.param.k) + "_w" +
                                  std::to_string(info.param.width) + (info.param.simd.empty() ? "" : "_") +
                                  info.param.simd;
                         });

}  // namespace
}  // namespace ccdlab
