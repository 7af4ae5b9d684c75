#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <set>

#include "framework/geometry/kdop.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

template <int K>
void check_axis_table() {
  const auto& axes = KDop<K>::axes;
  ASSERT_EQ(int(axes.size()), K / 2);
  // The first three are the coordinate axes (K = 6 is the AABB).
  EXPECT_EQ((axes[0]), (std::array<int, 3>{1, 0, 0}));
  EXPECT_EQ((axes[1]), (std::array<int, 3>{0, 1, 0}));
  EXPECT_EQ((axes[2]), (std::array<int, 3>{0, 0, 1}));
  // No axis is parallel to another (each slab must add information).
  for (std::size_t i = 0; i < axes.size(); ++i)
    for (std::size_t j = i + 1; j < axes.size(); ++j) {
      Eigen::Vector3d a(axes[i][0], axes[i][1], axes[i][2]), b(axes[j][0], axes[j][1], axes[j][2]);
      EXPECT_GT(a.cross(b).norm(), 0.5) << "axes " << i << " and " << j << " of K=" << K << " are parallel";
    }
}

TEST(KDopAxes, TablesMatchThePaper) {
  check_axis_table<6>();
  check_axis_table<14>();
  check_axis_table<18>();
  check_axis_table<26>();
  // K = 14: the 4 corner diagonals; K = 18: the 6 edge diagonals; K = 26: both.
  auto count = [](const auto& axes, int nonzeros) {
    int n = 0;
    for (const auto& a : axes) n += (a[0] != 0) + (a[1] != 0) + (a[2] != 0) == nonzeros;
    return n;
  };
  EXPECT_EQ(count(KDop<14>::axes, 3), 4);
  EXPECT_EQ(count(KDop<14>::axes, 2), 0);
  EXPECT_EQ(count(KDop<18>::axes, 2), 6);
  EXPECT_EQ(count(KDop<18>::axes, 3), 0);
  EXPECT_EQ(count(KDop<26>::axes, 3), 4);
  EXPECT_EQ(count(KDop<26>::axes, 2), 6);
}

template <class BV>
void check_swept_contains_motion(double scale, double offset) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Vec3 p[6];
    for (Vec3& q : p) q = offset * Vec3::Ones() + scale * Vec3(u(rng), u(rng), u(rng));
    // A triangle's swept volume: under linear motion every point of it stays in the hull of these 6 points.
    BV bv;
    bv.grow(std::array<const Vec3*, 6>{&p[0], &p[1], &p[2], &p[3], &p[4], &p[5]});
    for (int s = 0; s <= 10; ++s) {
      const double t = s / 10.0;
      const double w1 = 0.5 * (u(rng) + 1), w2 = (1 - w1) * 0.5 * (u(rng) + 1);
      Vec3 a = (1 - t) * p[0] + t * p[3], b = (1 - t) * p[1] + t * p[4], c = (1 - t) * p[2] + t * p[5];
      for (const Vec3& q : {a, b, c, Vec3((1 - w1 - w2) * a + w1 * b + w2 * c)})
        ASSERT_TRUE(bv.contains(q)) << "K=" << BV::k << " trial " << trial << " t=" << t;
    }
  }
}

TEST(KDop, GrownOverBothFramesContainsEveryPointOfTheMotion) {
  for (double scale : {1e-6, 1.0, 1e6})
    for (double offset : {0.0, 1e3, -1e7}) {
      check_swept_contains_motion<KDop<6>>(scale, offset);
      check_swept_contains_motion<KDop<14>>(scale, offset);
      check_swept_contains_motion<KDop<18>>(scale, offset);
      check_swept_contains_motion<KDop<26>>(scale, offset);
    }
}

TEST(KDop, TouchingVolumesOverlapAndSeparatedOnesDoNot) {
  KDop<18> a, b, c;
  a.grow(Vec3(0, 0, 0));
  a.grow(Vec3(1, 1, 1));
  b.grow(Vec3(1, 1, 1));  // touches a at a corner
  b.grow(Vec3(2, 2, 2));
  c.grow(Vec3(1.5, 0, 0));
  c.grow(Vec3(2, 0.2, 0.2));
  EXPECT_TRUE(a.overlaps(b));
  EXPECT_TRUE(b.overlaps(a));
  // c's AABB overlaps a's? No: x in [1.5, 2] vs [0, 1].
  EXPECT_FALSE(a.overlaps(c));
  // A case only the diagonal axes separate: boxes overlap, 18-DOPs do not.
  KDop<6> box_a, box_d;
  KDop<18> dop_a, dop_d;
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}) box_a.grow(p), dop_a.grow(p);
  for (const Vec3& p : {Vec3(1, 1, 0), Vec3(0.9, 0.9, 0), Vec3(1, 0.8, 0)}) box_d.grow(p), dop_d.grow(p);
  EXPECT_TRUE(box_a.overlaps(box_d));
  EXPECT_FALSE(dop_a.overlaps(dop_d));
}

template <int K>
void check_overlaps_against_every_axis() {
  // overlaps() compares four axes at a time where it can; the reference is one axis at a time. Small random
  // triangles at random offsets: many pairs are apart on exactly one axis, and every axis is that one for some.
  std::mt19937 rng(K);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<int> only_axis(KDop<K>::num_axes, 0);
  int overlapping = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    KDop<K> a, b;
    const Vec3 offset(u(rng), u(rng), u(rng));
    for (int k = 0; k < 3; ++k) {
      a.grow(Vec3(u(rng), u(rng), u(rng)) * 0.3);
      b.grow(offset + Vec3(u(rng), u(rng), u(rng)) * 0.3);
    }
    int apart = 0, last = -1;
    for (int i = 0; i < KDop<K>::num_axes; ++i)
      if (a.min(i) > b.max(i) || b.min(i) > a.max(i)) ++apart, last = i;
    ASSERT_EQ(a.overlaps(b), apart == 0) << "K=" << K << " trial " << trial;
    ASSERT_EQ(b.overlaps(a), apart == 0) << "K=" << K << " trial " << trial;
    overlapping += apart == 0;
    if (apart == 1) ++only_axis[last];
  }
  EXPECT_GT(overlapping, 100) << "K=" << K;
  for (int i = 0; i < KDop<K>::num_axes; ++i) EXPECT_GT(only_axis[i], 0) << "K=" << K << " axis " << i;
}

TEST(KDop, OverlapsAgreesWithTheAxisByAxisTest) {
  check_overlaps_against_every_axis<6>();
  check_overlaps_against_every_axis<14>();
  check_overlaps_against_every_axis<18>();
  check_overlaps_against_every_axis<26>();
}

TEST(KDop, ThicknessInflatesEverySlabByTheProjectedRadius) {
  KDop<26> a, b;
  a.grow(Vec3(0, 0, 0));
  b.grow(Vec3(1, 1, 1));  // distance sqrt(3)
  KDop<26> a1 = a, b1 = b;
  a1.inflate(0.85);
  b1.inflate(0.85);  // 1.7 < sqrt(3) ≈ 1.732: separated on the (1,1,1) axis
  EXPECT_FALSE(a1.overlaps(b1));
  a.inflate(0.87);
  b.inflate(0.87);  // 1.74 > sqrt(3)
  EXPECT_TRUE(a.overlaps(b));
}

TEST(KDop, MergeIsTheUnion) {
  KDop<14> a, b, m;
  a.grow(Vec3(0, 0, 0));
  b.grow(Vec3(3, -2, 5));
  m = a;
  m.merge(b);
  EXPECT_TRUE(m.contains(Vec3(0, 0, 0)));
  EXPECT_TRUE(m.contains(Vec3(3, -2, 5)));
  EXPECT_TRUE(m.contains(Vec3(1.5, -1, 2.5)));
  EXPECT_FALSE(m.contains(Vec3(4, 0, 0)));
  EXPECT_TRUE(KDop<14>().empty());
  EXPECT_FALSE(KDop<14>().overlaps(m));
}


// The outward rounding every k-DOP relies on: round_down(x) is the largest float <= x, round_up(x) the
// smallest float >= x, at zeros, subnormals, the float range's ends, exact floats and doubles between them.
TEST(KDop, RoundingIsTheNearestFloatOutward) {
  const float inf = std::numeric_limits<float>::infinity();
  auto reference_down = [&](double x) {
    const auto f = static_cast<float>(x);
    return static_cast<double>(f) > x ? std::nextafter(f, -inf) : f;
  };
  auto reference_up = [&](double x) {
    const auto f = static_cast<float>(x);
    return static_cast<double>(f) < x ? std::nextafter(f, inf) : f;
  };
  std::vector<double> xs = {0.0, -0.0, 1.0, -1.0, 0.1, -0.1, 1e-45, -1e-45, 1e-40, -1e-40, 3.4028234663852886e38,
                            -3.4028234663852886e38, double(std::numeric_limits<float>::denorm_min()),
                            double(std::numeric_limits<float>::min()), -double(std::numeric_limits<float>::min())};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-140, 120);
  for (int i = 0; i < 100000; ++i) xs.push_back(std::ldexp(mantissa(rng), exponent(rng)));
  for (double x : xs) {
    const float lo = detail::round_down(x), hi = detail::round_up(x);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(lo), std::bit_cast<std::uint32_t>(reference_down(x))) << x;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(hi), std::bit_cast<std::uint32_t>(reference_up(x))) << x;
    EXPECT_LE(double(lo), x);
    EXPECT_GE(double(hi), x);
  }
}

}  // namespace
}  // namespace ccdlab
