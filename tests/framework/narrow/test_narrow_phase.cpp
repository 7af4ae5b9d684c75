// The batched narrow phase: its SIMD kernels agree with their plain versions on every SIMD target this machine
// can run (the scalar EMU128 target forced included), its culling stages never drop a pair the tester reports,
// and every mode and representative rule reports the same contacts.
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <memory>
#include <string>

#include "framework/narrow/kdop_filter.hpp"
#include "framework/util/simd_target.hpp"
#include "framework/narrow/narrow_phase.hpp"
#include "framework/narrow/window_distance_filter.hpp"
#include "framework/narrow/split_filter.hpp"
#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "strategies/testers/float_tester.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::for_each_simd_target;

/// Random moving pairs near each other at every scale, some exactly coplanar throughout, some degenerate.
PlaneBatch random_plane_batch(std::size_t n, std::mt19937& rng) {
  PlaneBatch b;
  b.resize(n);
  std::uniform_real_distribution<double> u(-1, 1), e(-6, 6);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::pow(10.0, e(rng));
    auto v = [&]() -> Vec3 { return Vec3(u(rng), u(rng), u(rng)) * s; };
    std::array<Vec3, 7> p;
    for (Vec3& q : p) q = v();
    if (i % 7 == 0)  // coplanar motion: f ≡ 0
      for (int k = 0; k < 6; ++k) p[k].z() = 0;
    if (i % 11 == 0) {  // degenerate: B ∥ C
      p[4] = 2 * p[2];
      p[5] = 2 * p[3];
    }
    b.set(i, p[0], p[1], p[2], p[3], p[4], p[5], p[6]);
  }
  return b;
}

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

/// Row 0: the VF query, row 1: the EE query, as the narrow phase stages them (NarrowPhase::cull_plane).
PlaneBatch rows_of(const VertexFaceQuery& q, const EdgeEdgeQuery& r) {
  PlaneBatch b;
  b.resize(2);
  b.set(0, q.v_t0 - q.f0_t0, q.v_t1 - q.f0_t1, q.f1_t0 - q.f0_t0, q.f1_t1 - q.f0_t1, q.f2_t0 - q.f0_t0,
        q.f2_t1 - q.f0_t1, q.f0_t1 - q.f0_t0);
  b.set(1, r.eb0_t0 - r.ea0_t0, r.eb0_t1 - r.ea0_t1, r.ea1_t0 - r.ea0_t0, r.ea1_t1 - r.ea0_t1,
        r.eb1_t0 - r.eb0_t0, r.eb1_t1 - r.eb0_t1, r.ea0_t1 - r.ea0_t0);
  return b;
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

/// n rows of random points in a thin slab: many pairs near contact, many planes crossing.
PlaneBatch near_contact_rows(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto p = [&]() -> Vec3 { return Vec3(u(rng), u(rng), 0.1 * u(rng)); };
  PlaneBatch b;
  b.resize(n);
  for (std::size_t i = 0; i < n; ++i) b.set(i, p(), p(), p(), p(), p(), p(), p());
  return b;
}

TEST(SplitFilter, EverySimdTargetAgreesWithThePlainVersion) {
  // Pairs near contact (stage 2 keeps many of them), at thickness 0 and > 0: stage 3's SIMD kernel against its
  // plain version, VF rows then EE rows as the narrow phase lays them out.
  const std::size_t n = 4001, nvf = 1777;
  PlaneBatch b = near_contact_rows(n, 21);
  for (CullReach reach : {CullReach{0, 2e-9}, CullReach{0.02, 2e-9}}) {
    std::vector<std::uint8_t> stage2(n);
    plane_filter(b, reach, stage2.data());
    for (const int levels : {kSplitCoarseLevels, kSplitLevels}) {
      std::vector<std::uint8_t> expect(n);
      std::vector<std::uint16_t> expect_open(n);
      std::size_t culled = 0, partly_open = 0;
      for (std::size_t i = 0; i < n; ++i) {
        expect_open[i] = split_filter_open(b, i, i < nvf, levels);
        culled += !(expect[i] = split_filter_keeps(b, i, i < nvf, levels));
        EXPECT_EQ(expect[i], expect_open[i] != 0);
        partly_open += expect_open[i] != 0 && expect_open[i] != (1u << (1 << levels)) - 1;
      }
      EXPECT_GT(culled, n / 10);
      EXPECT_GT(partly_open, n / 20);  // the masks mean something: many rows have some windows proven, not all
      for_each_simd_target([&](const char* target) {
        std::vector<std::uint8_t> keep(n, 1);
        std::vector<std::uint16_t> open(n, 0xABCD);
        split_filter(b, 0, nvf, true, keep.data(), levels, open.data());
        split_filter(b, nvf, n, false, keep.data(), levels, open.data());
        EXPECT_EQ(keep, expect) << target << " levels " << levels;
        EXPECT_EQ(open, expect_open) << target << " levels " << levels;
      });
    }
  }
}

TEST(SplitFilter, SixteenthsWithinTheOpenHalvesAgreeWithThePlainVersion) {
  // The sixteenths given the halves pass's open bits, as the narrow phase runs them (the bits read in place):
  // every row's windows within its open halves as the plain version finds them, the other half closed. Rows
  // are mostly one open half, in runs (whole vectors take the eight-window path) and mixed with rows where
  // both are open (their vectors take the sixteen-window path), on every target, at thickness 0 and > 0.
  const std::size_t n = 4001, nvf = 1777;
  PlaneBatch b = near_contact_rows(n, 22);
  std::mt19937 rng(5);
  std::vector<std::uint16_t> halves(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool mixed = (i / 64) % 2 == 1;  // runs of 64 rows: one open half each, then any of 1, 2, 3
    halves[i] = std::uint16_t(mixed ? 1 + rng() % 3 : 1 + rng() % 2);
  }
  for (CullReach reach : {CullReach{0, 2e-9}, CullReach{0.02, 2e-9}}) {
    std::vector<std::uint8_t> stage2(n);
    plane_filter(b, reach, stage2.data());
    std::vector<std::uint8_t> expect(n);
    std::vector<std::uint16_t> expect_open(n);
    std::size_t kept_by_other_half = 0;
    for (std::size_t i = 0; i < n; ++i) {
      expect_open[i] = split_filter_open(b, i, i < nvf, kSplitLevels, halves[i]);
      expect[i] = expect_open[i] != 0;
      const std::uint16_t all = split_filter_open(b, i, i < nvf, kSplitLevels);
      EXPECT_EQ(expect_open[i] & ~all, 0) << "row " << i;  // never opens a window the full pass closes
      kept_by_other_half += all != 0 && expect_open[i] == 0;
    }
    EXPECT_GT(kept_by_other_half, n / 20);  // the closed half matters: rows it alone drops are common
    for_each_simd_target([&](const char* target) {
      std::vector<std::uint8_t> keep(n, 1);
      std::vector<std::uint16_t> open = halves;
      split_filter(b, 0, nvf, true, keep.data(), kSplitLevels, open.data(), open.data());
      split_filter(b, nvf, n, false, keep.data(), kSplitLevels, open.data(), open.data());
      EXPECT_EQ(keep, expect) << target;
      EXPECT_EQ(open, expect_open) << target;
    });
  }
  std::vector<std::uint8_t> keep(1, 1);
  std::uint16_t open = 1;
  EXPECT_THROW(split_filter(b, 0, 1, true, keep.data(), kSplitCoarseLevels, &open, &open), Error);
}

TEST(ProximityFilter, EverySimdTargetAgreesWithThePlainVersion) {
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

TEST(ProximityFilter, NeverDropsAPairTheFloatTesterReports) {
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

TEST(SplitFilter, SixteenthsCullEveryPairTheHalvesCull) {
  // Running halves before sixteenths must only save work: a pair the halves drop, the sixteenths drop too.
  const std::size_t n = 20000;
  PlaneBatch b = near_contact_rows(n, 22);
  for (CullReach reach : {CullReach{0, 2e-9}, CullReach{0.02, 2e-9}}) {
    std::vector<std::uint8_t> stage2(n);
    plane_filter(b, reach, stage2.data());
    std::size_t halves_culled = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool vf = i % 2 == 0;
      if (split_filter_keeps(b, i, vf, kSplitCoarseLevels)) continue;
      ++halves_culled;
      EXPECT_FALSE(split_filter_keeps(b, i, vf, kSplitLevels)) << "row " << i;
    }
    EXPECT_GT(halves_culled, n / 10);
  }
}

/// Every VF pair (v ∉ f) and EE pair (no shared vertex) of a mesh.
struct AllFeaturePairs {
  std::vector<VertexFacePair> vf;
  std::vector<EdgeEdgePair> ee;
  explicit AllFeaturePairs(const TriMesh& mesh) {
    for (Index v = 0; v < mesh.num_vertices(); ++v)
      for (Index f = 0; f < mesh.num_faces(); ++f)
        if (!contains_vertex(mesh.face(f), v)) vf.push_back({v, f});
    for (Index a = 0; a < mesh.num_edges(); ++a)
      for (Index b = a + 1; b < mesh.num_edges(); ++b)
        if (!shares_vertex(mesh.edge(a), mesh.edge(b))) ee.push_back({a, b});
  }
  /// keep flags of the plain float or coarse test, VF then EE.
  std::vector<std::uint8_t> flags(const TriMesh& mesh, const FeatureBounds& bounds, bool coarse) const {
    std::vector<std::uint8_t> out;
    for (const auto& p : vf)
      out.push_back(coarse ? vf_may_touch_coarse(bounds, p.v, mesh.face(p.f)) : vf_may_touch(bounds, p.v, mesh.face(p.f)));
    for (const auto& p : ee) {
      const Edge &a = mesh.edge(p.a), &b = mesh.edge(p.b);
      out.push_back(coarse ? ee_may_touch_coarse(bounds, a, b) : ee_may_touch(bounds, a, b));
    }
    return out;
  }
};

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

/// face_dop<K> for one moving triangle: holds every point of the motion padded by r = thickness / 2 along each
/// axis, and lies inside the k-DOP grown from the 6 points with the same padding (per-vertex rounding is tighter).
template <int K>
void check_face_dop(double scale, double offset, double thickness, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const TriMesh mesh(3, {Face{0, 1, 2}});
  Positions x0(3), x1(3);
  for (Vec3& q : x0) q = offset * Vec3::Ones() + scale * Vec3(u(rng), u(rng), u(rng));
  for (Vec3& q : x1) q = offset * Vec3::Ones() + scale * Vec3(u(rng), u(rng), u(rng));
  for_each_simd_target([&](const char* target) {
    FeatureBounds bounds;
    PhaseTrace trace;
    bounds.update(x0, x1, thickness, 1, trace);
    const KDop<K> leaf = bounds.face_dop<K>(mesh.face(0));
    KDop<K> six;
    six.grow(std::array<const Vec3*, 6>{&x0[0], &x0[1], &x0[2], &x1[0], &x1[1], &x1[2]});
    six.inflate(0.5 * thickness);
    for (int i = 0; i < K / 2; ++i) {
      ASSERT_GE(leaf.min(i), six.min(i)) << "K=" << K << " axis " << i << " " << target;
      ASSERT_LE(leaf.max(i), six.max(i)) << "K=" << K << " axis " << i << " " << target;
    }
    for (int s = 0; s <= 10; ++s) {
      const double t = s / 10.0, w1 = 0.5 * (u(rng) + 1), w2 = (1 - w1) * 0.5 * (u(rng) + 1);
      const Vec3 a = (1 - t) * x0[0] + t * x1[0], b = (1 - t) * x0[1] + t * x1[1], c = (1 - t) * x0[2] + t * x1[2];
      const Vec3 q = (1 - w1 - w2) * a + w1 * b + w2 * c;
      for (int i = 0; i < K / 2; ++i) {
        const auto& d = KDop<K>::axes[std::size_t(i)];
        const Vec3 dir(d[0], d[1], d[2]);
        // q and its projection carry a few roundings of double: 1e-14 relative covers them.
        const double proj = dir.dot(q), pad = 0.5 * thickness * dir.norm(), slack = 1e-14 * (std::abs(proj) + pad);
        ASSERT_LE(double(leaf.min(i)), proj - pad + slack) << "K=" << K << " t=" << t;
        ASSERT_GE(double(leaf.max(i)), proj + pad - slack) << "K=" << K << " t=" << t;
      }
    }
  });
}

TEST(FeatureBounds, FaceDopHoldsTheMotionAndLiesInsideTheSixPointDop) {
  std::mt19937 rng(11);
  for (double scale : {1e-6, 1.0, 1e6})
    for (double offset : {0.0, 1e3, -1e7})
      for (double thickness : {0.0, 1e-3 * scale})
        for (int trial = 0; trial < 20; ++trial) {
          check_face_dop<6>(scale, offset, thickness, rng);
          check_face_dop<14>(scale, offset, thickness, rng);
          check_face_dop<18>(scale, offset, thickness, rng);
          check_face_dop<26>(scale, offset, thickness, rng);
        }
}

TEST(FeatureBounds, SimdKeepAgreesWithThePlainVersionOnEveryTarget) {
  MeshData g = test::grid(12, 12);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(5);
  Positions x0 = test::crumple(g.positions, rng, 0.05), x1 = test::crumple(g.positions, rng, 0.05);
  const AllFeaturePairs pairs(mesh);
  std::vector<std::uint8_t> first_coarse;
  for_each_simd_target([&](const char* target) {
    FeatureBounds bounds;  // the coarse copy is made by this target's quantizer
    PhaseTrace trace;
    bounds.update(x0, x1, 0.01, 1, trace);
    const auto expect = pairs.flags(mesh, bounds, false), expect_coarse = pairs.flags(mesh, bounds, true);
    const auto kept = std::count(expect.begin(), expect.end(), 1);
    EXPECT_GT(kept, 100);
    EXPECT_LT(std::size_t(kept), expect.size() / 2);
    std::vector<std::uint8_t> keep(expect.size()), keep_coarse(expect.size());
    const std::size_t nvf = pairs.vf.size();
    vf_keep(bounds, mesh, pairs.vf, keep.data());
    ee_keep(bounds, mesh, pairs.ee, keep.data() + nvf);
    vf_keep_coarse(bounds, mesh, pairs.vf, keep_coarse.data());
    ee_keep_coarse(bounds, mesh, pairs.ee, keep_coarse.data() + nvf);
    EXPECT_EQ(keep, expect) << target;
    EXPECT_EQ(keep_coarse, expect_coarse) << target;
    // The measuring version keeps the same pairs; each pair's gap is its largest separation sum on the grid, and
    // (gap − 2) grid steps are a distance its float 26-DOPs keep along that axis's unit direction.
    std::vector<std::uint8_t> keep_gap(expect.size());
    EXPECT_EQ(vf_keep_coarse_gap(bounds, mesh, std::span(pairs.vf).first(0), keep_gap.data()), 32767);
    std::size_t measured = 0;
    for (std::size_t i = 0; i < expect.size(); i += 7) {
      const bool vf = i < nvf;
      const int gap = vf ? vf_keep_coarse_gap(bounds, mesh, std::span(pairs.vf).subspan(i, 1), keep_gap.data() + i)
                         : ee_keep_coarse_gap(bounds, mesh, std::span(pairs.ee).subspan(i - nvf, 1), keep_gap.data() + i);
      EXPECT_EQ(keep_gap[i], expect_coarse[i]) << target << " pair " << i;
      std::array<Index, 4> u{}, w{};  // the vertices of each side
      std::size_t nu = 0, nw = 0;
      if (vf) {
        u[nu++] = pairs.vf[i].v;
        for (Index v : mesh.face(pairs.vf[i].f)) w[nw++] = v;
      } else {
        for (Index v : mesh.edge(pairs.ee[i - nvf].a)) u[nu++] = v;
        for (Index v : mesh.edge(pairs.ee[i - nvf].b)) w[nw++] = v;
      }
      int sums = 0;  // padding lanes: 0
      double distance = 0;
      for (int k = 0; k < PaddedDop::kAxes; ++k) {
        int umin = 32767, uneg = 32767, wmin = 32767, wneg = 32767;
        double fu_min = HUGE_VAL, fu_max = -HUGE_VAL, fw_min = HUGE_VAL, fw_max = -HUGE_VAL;
        for (std::size_t j = 0; j < nu; ++j) {
          const CoarseDop& c = bounds.coarse_dops()[u[j]];
          umin = std::min<int>(umin, c.min[k]), uneg = std::min<int>(uneg, c.neg_max[k]);
          fu_min = std::min<double>(fu_min, bounds.dops()[u[j]].min[k]), fu_max = std::max<double>(fu_max, bounds.dops()[u[j]].max[k]);
        }
        for (std::size_t j = 0; j < nw; ++j) {
          const CoarseDop& c = bounds.coarse_dops()[w[j]];
          wmin = std::min<int>(wmin, c.min[k]), wneg = std::min<int>(wneg, c.neg_max[k]);
          fw_min = std::min<double>(fw_min, bounds.dops()[w[j]].min[k]), fw_max = std::max<double>(fw_max, bounds.dops()[w[j]].max[k]);
        }
        sums = std::max({sums, std::clamp(umin + wneg, -32768, 32767), std::clamp(wmin + uneg, -32768, 32767)});
        const auto& axis = KDop<26>::axes[std::size_t(k)];
        distance = std::max(distance, std::max(fu_min - fw_max, fw_min - fu_max) /
                                          std::sqrt(double(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])));
      }
      EXPECT_EQ(gap, sums) << target << " pair " << i;
      EXPECT_LE((gap - 2) * bounds.coarse_step(), distance) << target << " pair " << i;
      measured += gap > 2;
    }
    EXPECT_GT(measured, 100u);
    if (first_coarse.empty()) first_coarse = keep_coarse;
    EXPECT_EQ(keep_coarse, first_coarse) << target << ": the quantizers of two targets disagree";
  });
}

TEST(FeatureBounds, SimdSweptDopsAreThePlainOnesOnEveryTarget) {
  // The vertices' float 26-DOPs define the contact set, so the SIMD pass must give the plain floats exactly: at
  // every scale, with the two frames equal or not, at zero, at thickness 0 and > 0, and with non-finite input.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1, 1), e(-35, 35);
  Positions x0, x1;
  for (int i = 0; i < 4000; ++i) {
    const double scale = std::pow(10.0, e(rng));
    const Vec3 p = scale * Vec3(u(rng), u(rng), u(rng));
    x0.push_back(p);
    switch (i % 4) {
      case 0: x1.push_back(p); break;                                                  // still
      case 1: x1.push_back(p + 1e-9 * scale * Vec3(u(rng), u(rng), u(rng))); break;    // barely moving
      default: x1.push_back(std::pow(10.0, e(rng)) * Vec3(u(rng), u(rng), u(rng)));  // anywhere
    }
  }
  x0.push_back(Vec3::Zero()), x1.push_back(Vec3::Zero());
  x0.push_back(Vec3(0, -0.0, 1)), x1.push_back(Vec3(-0.0, 0, 1));
  x0.push_back(Vec3(3e38, -3e38, 1)), x1.push_back(Vec3(1e300, 1, 1));  // beyond float range
  x0.push_back(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)), x1.push_back(Vec3(1, 2, 3));
  x0.push_back(Vec3(1, 2, 3)), x1.push_back(Vec3(0, -std::numeric_limits<double>::infinity(), 0));
  const auto same = [](float a, float b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  for (double r : {0.0, 1e-3, 0.37}) {
    std::vector<PaddedDop> expect;
    for (std::size_t v = 0; v < x0.size(); ++v) expect.push_back(swept_vertex_dop(x0[v], x1[v], r));
    for_each_simd_target([&](const char* target) {
      std::vector<PaddedDop> got(x0.size());
      detail::swept_vertex_dops(x0.data(), x1.data(), x0.size(), r, got.data());
      std::size_t wrong = 0;
      for (std::size_t v = 0; v < x0.size(); ++v)
        for (int i = 0; i < PaddedDop::kLanes; ++i) {
          const bool ok = same(got[v].min[i], expect[v].min[i]) && same(got[v].max[i], expect[v].max[i]);
          if (!ok && wrong++ < 3)
            ADD_FAILURE() << target << " r " << r << " vertex " << v << " axis " << i << ": " << got[v].min[i] << " "
                          << got[v].max[i] << " against " << expect[v].min[i] << " " << expect[v].max[i];
        }
      EXPECT_EQ(wrong, 0u) << target << " r " << r;
    });
  }
}

TEST(FeatureBounds, TheCoarseTestKeepsEveryPairTheFloatTestKeeps) {
  // Stage 1 runs the coarse test on every pair and the float one only at the end: a pair the float test keeps
  // and the coarse one dropped would be a lost contact. Ordinary frames, and the grid's edge cases: a flat axis
  // (extent 0), coordinates far from the origin (a float grid step of 1), tiny ones (denormal extents), NaN,
  // ±∞ and thickness. Two sheets side by side, the second starting exactly where the first ends (x = 1), so
  // that many pairs touch at equality: a grid that rounded minima and maxima apart would drop them.
  MeshData g = test::concat(test::grid(10, 10), test::grid(10, 10));
  for (std::size_t i = g.positions.size() / 2; i < g.positions.size(); ++i)
    g.positions[i].x() = 1.0 + 0.7 * g.positions[i].x();  // x = 1 off the grid's integer steps
  TriMesh mesh(Index(g.positions.size()), g.faces);
  const AllFeaturePairs pairs(mesh);
  std::mt19937 rng(17);
  struct Case {
    const char* name;
    Positions x0, x1;
    double thickness;
  };
  std::vector<Case> cases;
  cases.push_back({"crumpled", test::crumple(g.positions, rng, 0.04), test::crumple(g.positions, rng, 0.04), 0.0});
  cases.push_back({"crumpled, thick", test::crumple(g.positions, rng, 0.04), test::crumple(g.positions, rng, 0.04), 0.05});
  cases.push_back({"flat", g.positions, g.positions, 0.0});
  Case far{"far from the origin", test::crumple(g.positions, rng, 0.04), test::crumple(g.positions, rng, 0.04), 0.0};
  for (Positions* x : {&far.x0, &far.x1})
    for (Vec3& p : *x) p = 1e7 * Vec3(1, -1, 1) + 3.0 * p;
  cases.push_back(far);
  Case tiny{"tiny", test::crumple(g.positions, rng, 0.04), test::crumple(g.positions, rng, 0.04), 0.0};
  for (Positions* x : {&tiny.x0, &tiny.x1})
    for (Vec3& p : *x) p *= 1e-39;
  cases.push_back(tiny);
  Case nan{"NaN", test::crumple(g.positions, rng, 0.04), test::crumple(g.positions, rng, 0.04), 0.0};
  nan.x1[7].y() = std::numeric_limits<double>::quiet_NaN();
  cases.push_back(nan);
  Case inf{"infinite", test::crumple(g.positions, rng, 0.04), test::crumple(g.positions, rng, 0.04), 0.0};
  inf.x0[3].x() = std::numeric_limits<double>::infinity();
  inf.x1[50].z() = -std::numeric_limits<double>::infinity();
  cases.push_back(inf);
  for (const Case& c : cases) {
    FeatureBounds bounds;
    PhaseTrace trace;
    bounds.update(c.x0, c.x1, c.thickness, 1, trace);
    const auto fine = pairs.flags(mesh, bounds, false), coarse = pairs.flags(mesh, bounds, true);
    std::size_t fine_culled = 0, coarse_culled = 0;
    for (std::size_t i = 0; i < fine.size(); ++i) {
      ASSERT_TRUE(!fine[i] || coarse[i]) << c.name << ": pair " << i << " kept by the float test, dropped by the coarse one";
      fine_culled += !fine[i];
      coarse_culled += !coarse[i];
    }
    if (std::string(c.name).starts_with("crumpled")) {
      // It is a filter worth running: it drops nearly all the float test drops.
      EXPECT_GT(fine_culled, fine.size() / 2) << c.name;
      EXPECT_GE(coarse_culled, fine_culled * 99 / 100) << c.name;
    }
  }
}

/// A tester by name; "conservative+eta" is `conservative` at thickness 0.002 (1/50 of an edge of a 10×10 grid).
std::unique_ptr<PrimitiveTester> make_tester(const std::string& tester) {
  if (tester == "conservative+eta") {
    ParamValues p = tester_registry().find("conservative")->defaults();
    p.set("thickness", 0.002);
    return tester_registry().make({"conservative", p});
  }
  return tester_registry().make({tester, tester_registry().find(tester)->defaults()});
}

PipelineStrategies strategies(const char* tester, NarrowOptions narrow, int k, int threads) {
  PipelineStrategies s;
  s.k = k;
  s.threads = threads;
  s.narrow = narrow;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({"front", scheduler_registry().find("front")->defaults()});
  s.tester = make_tester(tester);
  return s;
}

TEST(SimdTargets, CcdlabSimdLimitsTheDispatchToTheNamedTargetOrALesserOne) {
  const std::string best = simd_target_name();
  limit_simd_target("scalar");
  const std::string scalar = simd_target_name();
  EXPECT_TRUE(scalar == "EMU128" || scalar == "SCALAR") << scalar;
  if (hwy::SupportedTargets() & HWY_AVX2) {
    limit_simd_target("avx2");
    EXPECT_STREQ(simd_target_name(), "AVX2");
  }
  limit_simd_target("avx512");  // the best this CPU has, AVX-512 or not
  EXPECT_EQ(simd_target_name(), best);
  EXPECT_THROW(limit_simd_target("avx1024"), Error);
  EXPECT_EQ(simd_target_name(), best);  // a refused name changes nothing
  hwy::SetSupportedTargetsForTest(0);
}

TEST(Gather, SimdGatherWritesThePlainLoopsPairsInItsOrderOnEveryTarget) {
  MeshData g = test::grid(14, 11);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  const Representatives reps(mesh, RepresentativeRule::fixed, [](Index) { return true; });
  // Every non-adjacent face pair, in a shuffled order: all owner combinations the grid has, both orders of ids.
  std::vector<FacePair> candidates;
  for (Index f = 0; f < mesh.num_faces(); ++f)
    for (Index h = 0; h < mesh.num_faces(); ++h)
      if (f != h && !mesh.faces_adjacent(f, h)) candidates.push_back({f, h});
  std::mt19937 rng(3);
  std::shuffle(candidates.begin(), candidates.end(), rng);
  std::set<unsigned> combinations;
  for (const FacePair& p : candidates)
    combinations.insert(unsigned(reps.owners().owned_mask[p.a]) | unsigned(reps.owners().owned_mask[p.b]) << 6);
  EXPECT_GT(combinations.size(), 60u);
  const std::vector<VertexFacePair> vf_before = {{1, 2}, {3, 4}};  // appended to, not replaced
  const std::vector<EdgeEdgePair> ee_before = {{5, 6}};
  auto gather = [&](std::span<const FacePair> c, bool simd) {
    FeatureBatch b;
    b.vf.insert(b.vf.end(), vf_before.begin(), vf_before.end());
    b.ee.insert(b.ee.end(), ee_before.begin(), ee_before.end());
    reps.append_pairs(c, b.vf, b.ee, simd);
    return std::pair(std::vector<VertexFacePair>(b.vf.begin(), b.vf.end()), std::vector<EdgeEdgePair>(b.ee.begin(), b.ee.end()));
  };
  const auto expect = gather(candidates, false);
  EXPECT_GT(expect.first.size(), candidates.size());
  for_each_simd_target([&](const char* target) {
    EXPECT_EQ(gather(candidates, true), expect) << target;
    for (std::size_t n : {0, 1, 7}) EXPECT_EQ(gather(std::span(candidates).first(n), true), gather(std::span(candidates).first(n), false)) << target;
  });
}

TEST(NarrowModes, EveryModeRuleTargetAndKReportsTheSameContactsAsBruteForce) {
  MeshData g = test::grid(10, 10);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(9);
  // Testers with a cull reach: the culling stages may only drop pairs they would not report.
  for (const char* tester : {"float", "filtered", "conservative", "conservative+eta"}) {
    Positions x0 = test::crumple(g.positions, rng, 0.03), x1 = x0;
    std::uniform_real_distribution<double> u(-1, 1);
    for (Vec3& p : x1) p += 0.1 * Vec3(u(rng), u(rng), u(rng));
    CollisionRules rules(mesh, single_cloth_body(mesh));
    auto reference = brute_force_contacts(mesh, rules, x0, x1, *strategies(tester, {}, 18, 1).tester, true);
    ASSERT_GT(reference.size(), 5u) << tester;
    const std::uint64_t expect = contact_set_hash(reference);
    for (auto mode : {NarrowMode::scalar, NarrowMode::batched})
      for (auto rule : {RepresentativeRule::fixed, RepresentativeRule::first_free})
        for (auto carry : {PassChoice::off, PassChoice::on})
          for (int k : {6, 14, 18, 26}) {
            if (carry == PassChoice::on && rule == RepresentativeRule::first_free) continue;  // nothing to carry
            CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies(tester, {mode, rule, {.orphan_carry = carry}}, k, 1 + k % 3));
            const StepResult r = pipeline.step(x0, x1);
            EXPECT_EQ(contact_set_hash(r.contacts), expect)
                << tester << " " << to_string(mode) << "/" << to_string(rule) << " K=" << k << " carry " << int(carry);
            if (carry == PassChoice::on) {
              EXPECT_GT(r.counters.orphans_carried, 0u) << tester << " K=" << k;
            }
          }
    for_each_simd_target([&](const char* target) {
      CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies(tester, {}, 18, 2));
      EXPECT_EQ(contact_set_hash(pipeline.step(x0, x1).contacts), expect) << tester << " on " << target;
    });
  }
}

TEST(NarrowModes, StageFourRunsWhereItsMeasuredSavingPaysAndTheContactsStayTheSame) {
  // A crumpled sheet mirrored through its plane, one step replayed: its folds pass through each other, so most
  // pairs that reach stage 4 are contacts. Forced on or off, stage 4 and the sixteenths leave the contacts of
  // brute force; adaptive, the pipeline runs them in its second step exactly when its first step's measured
  // thread-ns say they paid (rules/stage_rules.hpp), whichever way that comes out.
  MeshData g = test::grid(12, 12);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(17);
  const Positions x0 = test::crumple(g.positions, rng, 0.05);
  Positions x1 = x0;
  std::uniform_real_distribution<double> u(-1, 1);
  for (Vec3& p : x1) p.z() = -p.z() + 0.01 * u(rng);
  CollisionRules rules(mesh, single_cloth_body(mesh));
  for (const char* tester : {"float", "conservative"}) {
    const std::uint64_t expect = contact_set_hash(brute_force_contacts(mesh, rules, x0, x1, *make_tester(tester), true));
    for (const PassChoice sixteenths : {PassChoice::on, PassChoice::off})
      for (const PassChoice proximity : {PassChoice::on, PassChoice::off}) {
        CcdPipeline forced(mesh, single_cloth_body(mesh),
                           strategies(tester, {NarrowMode::batched, RepresentativeRule::fixed, {.sixteenths = sixteenths, .proximity = proximity}}, 18, 2));
        for (int s = 0; s < 2; ++s) {
          const StepResult r = forced.step(x0, x1);
          EXPECT_EQ(contact_set_hash(r.contacts), expect) << tester;
          EXPECT_EQ(r.counters.sixteenths_tested > 0, sixteenths == PassChoice::on) << tester;
          EXPECT_EQ(r.counters.proximity_tested > 0, sixteenths == PassChoice::on && proximity == PassChoice::on) << tester;
        }
      }
    CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies(tester, {}, 18, 2));
    const StepResult first = pipeline.step(x0, x1);
    EXPECT_EQ(contact_set_hash(first.contacts), expect) << tester;
    const NarrowCounters& c = first.counters;
    ASSERT_GT(c.proximity_tested, 0u) << tester;
    ASSERT_GT(c.sixteenths_tested, 0u) << tester;
    const double per_test = double(c.test_ns) / double(c.vf_tests + c.ee_tests);
    const double stage4 = CullPassRule::net_saving(double(c.proximity_ns), c.proximity_culled, per_test);
    const bool sixteenths_pay =
        CullPassRule::net_saving(double(c.sixteenths_ns), c.sixteenths_culled, per_test) + std::max(0.0, stage4) > 0;
    const StepResult second = pipeline.step(x0, x1);
    EXPECT_EQ(contact_set_hash(second.contacts), expect) << tester;
    EXPECT_EQ(second.counters.sixteenths_tested > 0, sixteenths_pay) << tester;
    EXPECT_EQ(second.counters.proximity_tested > 0, sixteenths_pay && stage4 > 0) << tester;
  }
}

/// `count` frames of grid `g`: crumpled (0.004), then each vertex jittered by up to `jitter` a step.
std::vector<Positions> drifting_sheet(const MeshData& g, unsigned seed, int count, double jitter) {
  std::mt19937 rng(seed);
  std::vector<Positions> frames{test::crumple(g.positions, rng, 0.004)};
  std::uniform_real_distribution<double> u(-1, 1);
  while (int(frames.size()) < count) {
    frames.push_back(frames.back());
    for (Vec3& p : frames.back()) p += jitter * Vec3(u(rng), u(rng), u(rng));
  }
  return frames;
}

TEST(OrphanCertificates, ABudgetLosesTheBlocksBendingNotItsTranslationNorAStepBackwards) {
  // One block: a vertex and a face of a 3×3 grid, 0.5 apart in x; its budget as if it was measured at 0.4.
  MeshData g = test::grid(3, 3);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  OrphanSet set;
  set.vf.push_back({0, mesh.num_faces() - 1});
  OrphanCertificates cert(set, mesh);
  ASSERT_EQ(cert.blocks(), 1u);
  const Positions x0 = g.positions;
  Positions x1 = x0;
  for (Vec3& p : x1) p.z() += 0.01;
  cert.begin_step(x0, x1, 0);
  EXPECT_FALSE(cert.holds(0));  // the first step: nothing measured
  cert.certify(0, 0.4f);
  EXPECT_TRUE(cert.holds(0));
  auto moved = [](Positions x, const Vec3& by, Index only = -1) {
    for (std::size_t v = 0; v < x.size(); ++v)
      if (only < 0 || Index(v) == only) x[v] += by;
    return x;
  };
  cert.begin_step(moved(x0, {0.3, 0.2, 1}), moved(x1, {0.3, 0.2, 1}), 0);  // the whole mesh translated
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1}), moved(x0, {0.3, 0.2, 1}), 0);  // the same step backwards
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // vertex 0 alone moves by 0.1
  EXPECT_FALSE(cert.holds(0));  // 0.4 − |(0.3, 0.2, 1)| < 0
  cert.certify(0, 0.4f);
  cert.begin_step(moved(x1, {0.3, 0.2, 1}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // unmoved since
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1.3}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // bent by 0.3: 0.1 left
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1.45}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // 0.15 more: spent
  EXPECT_FALSE(cert.holds(0));
  cert.certify(0, 0.4f);
  Positions nan = moved(x1, {0.3, 0.2, 1.45}, 0);
  nan[5].x() = std::numeric_limits<double>::quiet_NaN();
  cert.begin_step(nan, moved(x0, {0.3, 0.2, 1}), 0);  // a NaN anywhere: nothing holds
  EXPECT_FALSE(cert.holds(0));
  cert.certify(0, -0.1f);  // a block with an overlapping pair never holds
  cert.begin_step(moved(x1, {0.3, 0.2, 1.45}, 0), moved(x0, {0.3, 0.2, 1}), 0);
  EXPECT_FALSE(cert.holds(0));
}

TEST(NarrowModes, OrphanBlocksThatBarelyMovedAreSkippedWithTheSameContacts) {
  // A crumpled sheet that barely moves for a few steps, then one vertex passes through its neighbours (contacts
  // among the orphans) and back: the orphan loop skips blocks from the second step on, except where
  // the vertex moved, and reports the contacts of the scalar mode (which tests every orphan) at every step.
  MeshData g = test::grid(24, 24);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::vector<Positions> frames = drifting_sheet(g, 8, 7, 1e-4);
  frames[3][312] += Vec3(0, 0, 0.1);                           // lifted, then
  frames[4][312] = frames[3][312] + Vec3(0.08, 0.0, -0.11);      // through the sheet beside it, then back
  const NarrowOptions never_carry{NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::off, .certificates = PassChoice::on}};
  CcdPipeline batched(mesh, single_cloth_body(mesh), strategies("float", never_carry, 18, 2));
  CcdPipeline scalar(mesh, single_cloth_body(mesh), strategies("float", {NarrowMode::scalar, RepresentativeRule::fixed, {.orphan_carry = PassChoice::off}}, 18, 1));
  const std::size_t orphans = batched.orphans().vf.size() + batched.orphans().ee.size();
  for (std::size_t s = 0; s + 1 < frames.size(); ++s) {
    const StepResult a = batched.step(frames[s], frames[s + 1]), b = scalar.step(frames[s], frames[s + 1]);
    EXPECT_EQ(contact_set_hash(a.contacts), contact_set_hash(b.contacts)) << "step " << s;
    EXPECT_EQ(a.counters.orphans_unmoved + a.counters.orphan_vf + a.counters.orphan_ee, orphans) << "step " << s;
    if (s == 0) EXPECT_EQ(a.counters.orphans_unmoved, 0u);
    else EXPECT_GT(a.counters.orphans_unmoved, orphans / 2) << "step " << s;
    if (s == 3) {  // contacts among the orphans: the blocks that moved were tested
      const OrphanSet& o = batched.orphans();
      std::size_t among_orphans = 0;
      for (const Contact& c : a.contacts)
        among_orphans += c.kind == ContactKind::vf
                             ? std::count(o.vf.begin(), o.vf.end(), VertexFacePair{c.feature_a, c.feature_b})
                             : std::count(o.ee.begin(), o.ee.end(), EdgeEdgePair{c.feature_a, c.feature_b});
      EXPECT_GT(among_orphans, 0u);
    }
  }
}

TEST(NarrowModes, CandidatesThatCarryTheOrphansFindTheContactsOfAPipelineThatNeverLetsThem) {
  // A cloth that barely moves, with a vertex jumping through its neighbours (contacts among the orphans): the
  // candidates carry the orphans in every step (narrow.rules.orphan_carry: on), and the orphan loop keeps only
  // those no face pair can carry; the contacts are those of a pipeline that never lets them.
  MeshData g = test::grid(24, 24);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::vector<Positions> frames = drifting_sheet(g, 4, 4, 0.004);
  frames[2][300] = frames[1][300] + Vec3(0, 0, 0.3);
  CcdPipeline carrying(mesh, single_cloth_body(mesh), strategies("float", {NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::on}}, 18, 2));
  CcdPipeline never(mesh, single_cloth_body(mesh), strategies("float", {NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::off}}, 18, 2));
  const std::size_t orphans = carrying.orphans().vf.size() + carrying.orphans().ee.size();
  bool any_contact = false;
  for (std::size_t s = 0; s + 1 < frames.size(); ++s) {
    const StepResult a = carrying.step(frames[s], frames[s + 1]), b = never.step(frames[s], frames[s + 1]);
    EXPECT_EQ(contact_set_hash(a.contacts), contact_set_hash(b.contacts)) << "step " << s;
    EXPECT_EQ(b.counters.orphans_carried, 0u);
    EXPECT_EQ(b.counters.orphan_vf + b.counters.orphan_ee, orphans);
    EXPECT_GT(a.counters.orphans_carried, 0u) << "step " << s;
    EXPECT_LT(a.counters.orphan_vf + a.counters.orphan_ee, orphans / 10) << "step " << s;
    any_contact |= !a.contacts.empty();
  }
  EXPECT_TRUE(any_contact);
}

}  // namespace
}  // namespace ccdlab
