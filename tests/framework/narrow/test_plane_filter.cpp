// Stage 2 (plane_filter.hpp): every SIMD target agrees with the plain version, staging writes the plain rows,
// and no pair the float tester reports is dropped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "framework/narrow/split_filter.hpp"
#include "strategies/testers/float_tester.hpp"
#include "support/narrow_batches.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::AllFeaturePairs;
using test::random_plane_batch;
using test::rows_of;

using test::for_each_simd_target;

TEST(PlaneFilter, EverySimdTargetAgreesWithThePlainVersion) {
  std::mt19937 rng(3);
  PlaneBatch batch = random_plane_batch(5003, rng);
  for (CullReach reach : {CullReach{0, 0}, CullReach{0, 2e-9}, CullReach{1e-3, 2e-9}}) {
    std::vector<std::uint8_t> expect(batch.size());
    std::size_t culled = 0;
    for (std::size_t i = 0; i < batch.size(); ++i) culled += !(expect[i] = plane_filter_keeps(batch, i, reach));
    EXPECT_GT(culled, batch.size() / 20);  // the test means something: many pairs are culled
    for_each_simd_target([&](const char* target) {
      std::vector<std::uint8_t> keep(batch.size(), 7);
      plane_filter(batch, reach, keep.data());
      EXPECT_EQ(keep, expect) << target;
    });
  }
}


TEST(PlaneFilter, NeverDropsAPairTheFloatTesterReports) {
  // Random VF and EE queries in near contact (at thickness 0 and > 0): whatever the tester reports as a hit,
  // stages 2 and 3 keep, at the reach the tester declares.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double eta : {0.0, 0.02}) {
    FloatTester tester(FloatTester::Params{eta});
    const CullReach reach = *tester.cull_reach();
    int hits = 0, culled = 0, split_culled = 0;
    for (int i = 0; i < 20000; ++i) {
      auto p = [&] { return Vec3(u(rng), u(rng), 0.1 * u(rng)); };
      VertexFaceQuery q{p(), p(), p(), p(), p(), p(), p(), p()};
      EdgeEdgeQuery r{p(), p(), p(), p(), p(), p(), p(), p()};
      PlaneBatch b = rows_of(q, r);
      std::uint8_t keep[2];
      plane_filter(b, reach, keep);
      const bool hit_vf = tester.vertex_face(q).hit, hit_ee = tester.edge_edge(r).hit;
      hits += hit_vf + hit_ee;
      culled += !keep[0] + !keep[1];
      const bool split_vf = split_filter_keeps(b, 0, true), split_ee = split_filter_keeps(b, 1, false);
      split_culled += (keep[0] && !split_vf) + (keep[1] && !split_ee);
      if (hit_vf) {
        ASSERT_TRUE(keep[0] && split_vf) << "eta " << eta << " query " << i;
      }
      if (hit_ee) {
        ASSERT_TRUE(keep[1] && split_ee) << "eta " << eta << " query " << i;
      }
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(culled, 1000);
    EXPECT_GT(split_culled, 500);  // stage 3 removes many of what stage 2 keeps
  }
}


TEST(PlaneFilter, SimdStagingWritesThePlainRowsOnEveryTarget) {
  MeshData g = test::grid(9, 8);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(8);
  Positions x0 = test::crumple(g.positions, rng, 0.05), x1 = test::crumple(g.positions, rng, 0.05);
  std::uniform_real_distribution<double> e(-3, 3);
  for (Vec3& p : x1) p *= std::pow(10.0, e(rng));  // every scale, so that no two rows round alike by luck
  AllFeaturePairs all(mesh);
  std::shuffle(all.vf.begin(), all.vf.end(), rng);
  std::shuffle(all.ee.begin(), all.ee.end(), rng);
  const std::vector<VertexFacePair> vf(all.vf.begin(), all.vf.begin() + 1003);  // not a multiple of 4 or 8
  const std::vector<EdgeEdgePair> ee(all.ee.begin(), all.ee.begin() + 1001);
  // The rows as the narrow phase wrote them before it staged in SIMD: PlaneBatch::set, one pair at a time.
  PlaneBatch expect;
  expect.resize(vf.size() + ee.size());
  for (std::size_t i = 0; i < vf.size(); ++i) {
    const Face& f = mesh.face(vf[i].f);
    const Index v = vf[i].v;
    expect.set(i, x0[v] - x0[f[0]], x1[v] - x1[f[0]], x0[f[1]] - x0[f[0]], x1[f[1]] - x1[f[0]], x0[f[2]] - x0[f[0]],
               x1[f[2]] - x1[f[0]], x1[f[0]] - x0[f[0]]);
  }
  for (std::size_t i = 0; i < ee.size(); ++i) {
    const Edge &a = mesh.edge(ee[i].a), &b = mesh.edge(ee[i].b);
    expect.set(vf.size() + i, x0[b[0]] - x0[a[0]], x1[b[0]] - x1[a[0]], x0[a[1]] - x0[a[0]], x1[a[1]] - x1[a[0]],
               x0[b[1]] - x0[b[0]], x1[b[1]] - x1[b[0]], x1[a[0]] - x0[a[0]]);
  }
  std::vector<FramePoints> points(x0.size());
  interleave_frames(x0.data(), x1.data(), points.size(), points.data());
  for_each_simd_target([&](const char* target) {
    PlaneBatch got;
    got.resize(expect.size());
    stage_vf_rows(got, 0, vf, mesh.faces().data(), points.data());
    stage_ee_rows(got, vf.size(), ee, mesh.edges().data(), points.data());
    stage_ee_rows(got, got.size(), {}, mesh.edges().data(), points.data());  // no rows: writes nothing
    for (int c = 0; c < PlaneBatch::kColumns; ++c)
      for (std::size_t i = 0; i < expect.size() + PlaneBatch::kPad; ++i)  // the padding rows stay zero
        ASSERT_EQ(got.column(c)[i], expect.column(c)[i]) << target << " column " << c << " row " << i;
  });
}

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab
