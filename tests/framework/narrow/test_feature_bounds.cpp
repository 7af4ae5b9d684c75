// Stage 1 (narrow/kdop_filter.hpp over framework/swept/): a face's swept k-DOP holds its motion, the SIMD swept
// volumes and keep masks are the plain ones on every target, and the coarse test keeps what the float test keeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "framework/narrow/kdop_filter.hpp"
#include "support/narrow_batches.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::AllFeaturePairs;

using test::for_each_simd_target;

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

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab
