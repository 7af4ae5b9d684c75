// Stage 4 (window_distance_filter.hpp): every SIMD target against the plain version, and no pair the float
// tester reports dropped, on pairs brought near each other on purpose (beside a face, edges crossing beyond their ends).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "framework/narrow/window_distance_filter.hpp"
#include "framework/narrow/split_filter.hpp"
#include "strategies/testers/float_tester.hpp"
#include "support/narrow_batches.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::near_contact_rows;
using test::random_plane_batch;
using test::rows_of;

using test::for_each_simd_target;

TEST(WindowDistanceFilter, EverySimdTargetAgreesWithThePlainVersion) {
  // Stage 4's SIMD kernel over (row, window) items against its plain version, VF rows then EE rows: on rows near
  // contact with stage 3's own open windows, and on rows at every scale, coplanar or degenerate (B ∥ C), with
  // random windows open. Rows whose keep flag is clear must stay clear; the kernel must cull a fair share.
  std::mt19937 rng(41);
  PlaneBatch near = near_contact_rows(4001, 23), wild = random_plane_batch(3001, rng);
  std::uniform_int_distribution<int> mask(0, 0xFFFF);
  for (PlaneBatch* b : {&near, &wild}) {
    const std::size_t n = b->size(), nvf = n * 4 / 9;
    for (CullReach reach : {CullReach{0, 2e-9}, CullReach{0.02, 2e-9}}) {
      std::vector<std::uint8_t> keep_in(n);
      plane_filter(*b, reach, keep_in.data());
      std::vector<std::uint16_t> open(n);
      for (std::size_t i = 0; i < n; ++i) open[i] = b == &near ? split_filter_open(*b, i, i < nvf) : std::uint16_t(mask(rng));
      std::vector<std::uint8_t> expect(n);
      std::size_t culled = 0;
      for (std::size_t i = 0; i < n; ++i) {
        expect[i] = keep_in[i] && window_distance_filter_keeps(*b, i, i < nvf, open[i], kSplitLevels);
        culled += keep_in[i] && open[i] && !expect[i];
      }
      EXPECT_GT(culled, n / 50) << "reach " << reach.abs;
      for_each_simd_target([&](const char* target) {
        std::vector<std::uint8_t> keep = keep_in;
        WindowDistanceItems items;
        window_distance_filter(*b, nvf, n, open.data(), kSplitLevels, keep.data(), items);
        EXPECT_EQ(keep, expect) << target << " reach " << reach.abs;
      });
    }
  }
}


Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

/// A VF or EE query whose features come about `gap` apart at time `t_star` — off the face's (the other edge's)
/// plane, or `beside` it, in that plane (where f = 0: stages 2 and 3 cannot tell) — moving with random velocities
/// of size up to `speed` over the step.
VertexFaceQuery vf_near(std::mt19937& rng, double t_star, double gap, double speed, bool beside) {
  std::uniform_real_distribution<double> u(-1, 1);
  auto r = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  const Vec3 f0(0, 0, 0), f1(1, 0.1 * u(rng), 0), f2(0.2 * u(rng), 1, 0);
  const Vec3 p = beside ? Vec3(std::min(0.0, f2.x()) - gap, 0.3, 0) : Vec3(0.3 * f1 + 0.3 * f2 + Vec3(0, 0, gap));
  std::array<Vec3, 4> x{p, f0, f1, f2}, v;
  for (Vec3& w : v) w = speed * r();
  const Eigen::Matrix3d R = random_rotation(rng);  // so that boxes (stage 3) do not separate them
  auto at = [&](int k, double t) { return Vec3(R * (x[k] + (t - t_star) * v[k])); };
  return {at(0, 0), at(1, 0), at(2, 0), at(3, 0), at(0, 1), at(1, 1), at(2, 1), at(3, 1)};
}
EdgeEdgeQuery ee_near(std::mt19937& rng, double t_star, double gap, double speed, bool beside) {
  std::uniform_real_distribution<double> u(-1, 1), s(0.1, 0.9);
  auto r = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  const double sa = s(rng), sb = s(rng);
  const Vec3 off = beside ? Vec3(1 - sa + gap, 0, 0) : Vec3(0, 0, gap);  // beside: b crosses a's line past a1
  const Vec3 a0(-sa, 0, 0), a1(1 - sa, 0, 0), b0 = Vec3(0, -sb, 0) + off, b1 = Vec3(0, 1 - sb, 0) + off;
  std::array<Vec3, 4> x{a0, a1, b0, b1}, v;
  for (Vec3& w : v) w = speed * r();
  const Eigen::Matrix3d R = random_rotation(rng);  // so that boxes (stage 3) do not separate them
  auto at = [&](int k, double t) { return Vec3(R * (x[k] + (t - t_star) * v[k])); };
  return {at(0, 0), at(1, 0), at(2, 0), at(3, 0), at(0, 1), at(1, 1), at(2, 1), at(3, 1)};
}


TEST(WindowDistanceFilter, NeverDropsAPairTheFloatTesterReports) {
  // Features that come within (or just beyond) the reach at a random time, at thickness 0 and > 0, slow and fast:
  // whatever the float tester reports, stages 2, 3 and 4 keep. Stage 4 must also drop nearly all the slow pairs
  // that stay far apart (≥ 0.1, moving ≤ 0.05·√3) that stage 3 keeps, or this test would prove nothing.
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> time(0, 1), unit(0, 1);
  for (double eta : {0.0, 0.01}) {
    FloatTester tester(FloatTester::Params{eta});
    const CullReach reach = *tester.cull_reach();
    int hits = 0, far_kept = 0, far_culled = 0;
    for (int i = 0; i < 20000; ++i) {
      const double t_star = i % 5 == 0 ? std::floor(16 * time(rng)) / 16 : time(rng);  // window ends too
      const double scale = eta + 1e-6;
      const double gap = i % 3 == 0 ? scale * unit(rng) : i % 3 == 1 ? scale * (1 + unit(rng)) : 0.3 * unit(rng);
      const double speed = i % 2 == 0 ? 0.05 : 2.0;
      const bool beside = i % 4 < 2;
      const VertexFaceQuery q = vf_near(rng, t_star, gap, speed, beside);
      const EdgeEdgeQuery r = ee_near(rng, t_star, gap, speed, beside);
      PlaneBatch b = rows_of(q, r);
      std::uint8_t keep[2];
      plane_filter(b, reach, keep);
      const bool hit[2] = {tester.vertex_face(q).hit, tester.edge_edge(r).hit};
      for (int k = 0; k < 2; ++k) {
        const std::uint16_t open = keep[k] ? split_filter_open(b, std::size_t(k), k == 0) : 0;
        const bool stage4 = open && window_distance_filter_keeps(b, std::size_t(k), k == 0, open, kSplitLevels);
        hits += hit[k];
        const bool far = speed < 1 && gap >= 0.1;
        far_kept += far && open;
        far_culled += far && open && !stage4;
        if (hit[k]) {
          ASSERT_TRUE(stage4) << (k ? "EE" : "VF") << " eta " << eta << " query " << i << " gap " << gap;
        }
      }
    }
    EXPECT_GT(hits, 4000) << "eta " << eta;
    EXPECT_GT(far_kept, 300) << "eta " << eta;
    EXPECT_GT(far_culled, far_kept * 9 / 10) << "eta " << eta << ": stage 4 dropped too few to mean anything";
  }
}

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab
