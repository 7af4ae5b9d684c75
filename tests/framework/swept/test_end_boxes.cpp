// End boxes (framework/swept/end_boxes.hpp): each float bound holds its exact bound moved out by r, however the
// coordinates round; boxes apart at both ends on one axis keep every point pair of the step farther than 2r; and
// the wide walks' lane tests answer as the scalar test does, lane by lane.
#include <gtest/gtest.h>

#include <random>

#include "framework/swept/end_boxes.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/traversal/wide_overlap.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

FramePoints point(const Vec3& a, const Vec3& b) {
  FramePoints p{};
  for (int j = 0; j < 3; ++j) p.t0[j] = a[j], p.t1[j] = b[j];
  return p;
}

TEST(EndBoxes, EachBoundHoldsTheExactBoundMovedOutByTheReachWhateverTheRounding) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int rounded = 0;
  for (double scale : {1e-3, 1.0, 3e5, 1e7}) {
    for (int trial = 0; trial < 500; ++trial) {
      FramePoints pts[3];
      for (auto& p : pts) p = point(scale * Vec3(u(rng), u(rng), u(rng)), scale * Vec3(u(rng), u(rng), u(rng)));
      const double r = trial % 3 == 0 ? 0.0 : 1e-4 * scale * std::abs(u(rng));
      const EndBoxes e = face_end_boxes(pts, Face{0, 1, 2}, r);
      for (int c = 0; c < 3; ++c) {
        const double lo0 = std::min({pts[0].t0[c], pts[1].t0[c], pts[2].t0[c]}), hi0 = std::max({pts[0].t0[c], pts[1].t0[c], pts[2].t0[c]});
        const double lo1 = std::min({pts[0].t1[c], pts[1].t1[c], pts[2].t1[c]}), hi1 = std::max({pts[0].t1[c], pts[1].t1[c], pts[2].t1[c]});
        EXPECT_LE(double(e.lo[0][c]), lo0 - r);
        EXPECT_GE(double(e.hi[0][c]), hi0 + r);
        EXPECT_LE(double(e.lo[1][c]), lo1 - r);
        EXPECT_GE(double(e.hi[1][c]), hi1 + r);
        rounded += double(float(lo0 - r)) > lo0 - r;  // where plain rounding would have cut into the box
        // Loose only by the margin: a few float ulps of the bound.
        EXPECT_LT(lo0 - r - double(e.lo[0][c]), 8e-7 * (std::abs(lo0) + r) + 1e-30);
      }
    }
  }
  EXPECT_GT(rounded, 100) << "the coordinates must exercise rounding toward the box";
}

TEST(EndBoxes, ApartOnlyOnTheSameSideAtBothEnds) {
  // A unit box at the origin; the other moves along x. Apart at both ends on the same side: apart. Swapping sides
  // between t0 and t1 (passing through): not apart, whatever the gap at each end. Touching: not apart.
  const auto box = [](double x0, double x1) {
    FramePoints pts[3] = {point(Vec3(x0, 0, 0), Vec3(x1, 0, 0)), point(Vec3(x0 + 1, 1, 0), Vec3(x1 + 1, 1, 0)),
                          point(Vec3(x0, 1, 1), Vec3(x1, 1, 1))};
    return face_end_boxes(pts, Face{0, 1, 2}, 0.0);
  };
  const EndBoxes a = box(0, 0);
  EXPECT_TRUE(apart_at_both_ends(a, box(2, 3)));
  EXPECT_TRUE(apart_at_both_ends(box(2, 3), a));
  EXPECT_TRUE(apart_at_both_ends(a, box(-3, -2)));
  EXPECT_FALSE(apart_at_both_ends(a, box(3, -3))) << "passes through the box";
  EXPECT_FALSE(apart_at_both_ends(a, box(2, 0.5))) << "overlaps at t1";
  EXPECT_FALSE(apart_at_both_ends(a, box(1, 2))) << "touches at t0";
  EndBoxes nan = box(2, 3);
  nan.lo[0][0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(apart_at_both_ends(a, nan)) << "a NaN bound proves nothing";
}

#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
CCDLAB_AVX512_TARGET unsigned apart_avx512_for_test(const WideEnds& a, const WideEnds& b) {
  return lane_pairs_apart_at_both_ends(a, b);
}
CCDLAB_AVX2_TARGET unsigned apart_avx2_for_test(const WideEnds& a, const WideEnds& b) {
  return lane_pairs_apart_at_both_ends_avx2(a, b);
}
#endif

TEST(EndBoxes, LaneTestsAnswerAsTheScalarTestLaneByLane) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto random_ends = [&] {
    FramePoints pts[3];
    const Vec3 c0(u(rng), u(rng), u(rng)), c1 = c0 + 0.8 * Vec3(u(rng), u(rng), u(rng));
    for (auto& p : pts) p = point(c0 + 0.2 * Vec3(u(rng), u(rng), u(rng)), c1 + 0.2 * Vec3(u(rng), u(rng), u(rng)));
    return face_end_boxes(pts, Face{0, 1, 2}, 0.01);
  };
  const auto record = [](const EndBoxes (&lanes)[4]) {
    WideEnds w;
    for (int f = 0; f < 2; ++f)
      for (int c = 0; c < 3; ++c)
        for (int j = 0; j < 4; ++j) w.lo[f][c][j] = lanes[j].lo[f][c], w.hi[f][c][j] = lanes[j].hi[f][c];
    return w;
  };
  int apart = 0;
  for (int trial = 0; trial < 300; ++trial) {
    EndBoxes la[4], lb[4];
    for (int j = 0; j < 4; ++j) la[j] = random_ends(), lb[j] = random_ends();
    const WideEnds a = record(la), b = record(lb);
    unsigned expected = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) expected |= unsigned(apart_at_both_ends(la[i], lb[j])) << (4 * i + j);
    apart += std::popcount(expected);
    EXPECT_EQ(lane_pairs_apart_at_both_ends_plain(a, b), expected);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(lanes_apart_at_both_ends(b, a, i), (expected >> (4 * i)) & 0xFu);
#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
    if (lane_pair_walk() == LanePairWalk::avx512) {
      EXPECT_EQ(apart_avx512_for_test(a, b), expected);
    }
    if (lane_pair_walk() != LanePairWalk::none) {
      EXPECT_EQ(apart_avx2_for_test(a, b), expected);
    }
#endif
  }
  EXPECT_GT(apart, 300) << "the random boxes must be apart often";
  EXPECT_LT(apart, 300 * 16 - 300) << "and often not";
}

}  // namespace
}  // namespace ccdlab
