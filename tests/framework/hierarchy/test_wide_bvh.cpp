// The 4-wide view of a BVH (framework/hierarchy/wide_bvh.hpp): its lanes are exactly the grandchildren (a leaf
// child standing for itself), its bounds are the binary volumes, and the SIMD lane test agrees with
// KDop::overlaps (and with the plain loops) on every lane and lane pair — including identical volumes, which overlap
// (closed sets).
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <random>

#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/util/simd_target.hpp"
#include "framework/traversal/wide_overlap.hpp"
#include "strategies/builders/median_builder.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

BvhTopology grid_bvh(int n, int m, std::vector<Box3>& boxes, std::vector<Face>* faces_out = nullptr) {
  const MeshData g = test::grid(n, m);
  if (faces_out) faces_out->assign(g.faces.begin(), g.faces.end());
  std::vector<Index> faces;
  for (Index f = 0; f < Index(g.faces.size()); ++f) {
    faces.push_back(f);
    Box3 b;
    for (Index v : g.faces[std::size_t(f)]) b.grow(g.positions[std::size_t(v)]);
    boxes.push_back(b);
  }
  return MedianBuilder().build(faces, boxes);
}

TEST(WideBvh, LanesAreTheGrandchildren) {
  std::vector<Box3> boxes;
  std::vector<Face> faces;
  const BvhTopology bvh = grid_bvh(7, 5, boxes, &faces);  // 70 leaves: some inner nodes have a leaf child
  const WideLayout w = WideLayout::of(bvh, faces);
  ASSERT_EQ(w.version, bvh.version);
  std::size_t inner = 0, with_leaf_child = 0;
  for (Index i = 0; i < bvh.size(); ++i) {
    const BvhNode& n = bvh.nodes[i];
    if (n.is_leaf()) {
      EXPECT_EQ(w.slot[i], ~n.face) << "a leaf's slot names its face";
      continue;
    }
    ASSERT_EQ(w.slot[i], Index(inner)) << "inner nodes get slots in node order";
    std::vector<Index> expected;
    for (Index c : {n.left, n.right}) {
      if (bvh.nodes[c].is_leaf()) {
        expected.push_back(c);
        ++with_leaf_child;
      } else {
        expected.push_back(bvh.nodes[c].left);
        expected.push_back(bvh.nodes[c].right);
      }
    }
    const WideLayout::Lanes& l = w.lanes[inner];
    for (std::size_t j = 0; j < 4; ++j) {
      EXPECT_EQ(l.node[j], j < expected.size() ? expected[j] : -1) << "node " << i << " lane " << j;
      if (j < expected.size()) {
        EXPECT_EQ(l.slot[j], w.slot[l.node[j]]);
      } else {
        EXPECT_EQ(l.slot[j], WideLayout::kNoSlot) << "an empty lane's slot is no face's";
      }
      // A leaf lane carries its face's vertex ids (the lane-pair walk's adjacency test); others negative ids.
      for (std::size_t p = 0; p < 3; ++p) {
        const bool leaf = j < expected.size() && bvh.nodes[l.node[j]].is_leaf();
        if (leaf) {
          EXPECT_EQ(l.vert[p][j], faces[std::size_t(bvh.nodes[l.node[j]].face)][p]);
        } else {
          EXPECT_LT(l.vert[p][j], 0);
        }
      }
    }
    ++inner;
  }
  ASSERT_EQ(inner + 1, w.lanes.size()) << "one record per inner node, then the top record";
  const WideLayout::Lanes& top = w.lanes[std::size_t(w.top())];
  EXPECT_EQ(top.node[0], 0);
  EXPECT_EQ(top.node[1], bvh.nodes[0].left);
  EXPECT_EQ(top.node[2], bvh.nodes[0].right);
  EXPECT_EQ(top.node[3], -1);
  // Every node has a home: a lane that holds it, and the lane's slot is the node's.
  ASSERT_EQ(w.home.size(), bvh.nodes.size());
  for (Index i = 0; i < bvh.size(); ++i) {
    const Index h = w.home[std::size_t(i)];
    ASSERT_GE(h, 0) << "node " << i << " has no home";
    const WideLayout::Lanes& l = w.lanes[std::size_t(h / 4)];
    EXPECT_EQ(l.node[std::size_t(h % 4)], i);
    EXPECT_EQ(l.slot[std::size_t(h % 4)], w.slot[std::size_t(i)]);
  }
  EXPECT_GT(with_leaf_child, 0u) << "the tree must exercise leaf children standing for themselves";
}

TEST(WideBvh, ASingleLeafTreeHasATopRecord) {
  std::vector<Box3> boxes;
  std::vector<Face> faces;
  const BvhTopology bvh = grid_bvh(1, 1, boxes, &faces);  // two faces: a root and two leaves
  const WideLayout w = WideLayout::of(bvh, faces);
  ASSERT_EQ(w.lanes.size(), 2u);
  BvhTopology one = bvh;
  one.nodes.resize(1);
  one.nodes[0] = bvh.nodes[1];  // a leaf as the root
  const WideLayout w1 = WideLayout::of(one, faces);
  ASSERT_EQ(w1.lanes.size(), 1u);
  EXPECT_EQ(w1.home[0], 0);
  EXPECT_EQ(w1.lanes[0].slot[0], ~bvh.nodes[1].face);
}

#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
template <class BV>
CCDLAB_AVX512_TARGET unsigned lane_pairs_avx512_for_test(const WideBounds<BV>& a, const WideBounds<BV>& b) {
  return overlapping_lane_pairs(a, b);
}
template <class BV>
CCDLAB_AVX2_TARGET unsigned lane_pairs_avx2_for_test(const WideBounds<BV>& a, const WideBounds<BV>& b) {
  return overlapping_lane_pairs_avx2(a, b);
}
#endif

template <int K>
void check_lane_test(std::mt19937& rng) {
  using BV = KDop<K>;
  std::uniform_real_distribution<double> u(-1, 1);
  const auto random_dop = [&] {
    BV b;
    const Vec3 c(u(rng), u(rng), u(rng));
    for (int p = 0; p < 3; ++p) b.grow(c + 0.3 * Vec3(u(rng), u(rng), u(rng)));
    return b;
  };
  std::size_t hits = 0, misses = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::array<BV, 4> lane;
    for (auto& l : lane) l = random_dop();
    const int used = 2 + trial % 3;  // 2, 3 or 4 lanes, the rest empty
    WideBounds<BV> w;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < BV::num_axes; ++i) {
        w.lo[i][j] = j < used ? lane[j].min(i) : std::numeric_limits<float>::infinity();
        w.hi[i][j] = j < used ? lane[j].max(i) : -std::numeric_limits<float>::infinity();
      }
    // Every fourth query is a lane itself: touching and identical volumes must overlap.
    const BV q = trial % 4 == 0 ? lane[0] : random_dop();
    const unsigned mask = overlapping_lanes(w, q);
    EXPECT_EQ(mask, overlapping_lanes_plain(w, q)) << "SIMD and plain lane tests differ";
    // The same query read from a lane of another record (how the wide walk reads the other side).
    WideBounds<BV> holder;
    const int qj = trial % 4;
    for (int i = 0; i < BV::num_axes; ++i)
      for (int j = 0; j < 4; ++j) {
        holder.lo[i][j] = j == qj ? q.min(i) : std::numeric_limits<float>::quiet_NaN();
        holder.hi[i][j] = j == qj ? q.max(i) : std::numeric_limits<float>::quiet_NaN();
      }
    EXPECT_EQ(overlapping_lanes(w, WideLane<BV>{&holder, qj}), mask) << "a lane as the query";
    for (int j = 0; j < 4; ++j) {
      const bool expected = j < used && lane[j].overlaps(q);
      EXPECT_EQ(bool(mask >> j & 1u), expected) << "K=" << K << " trial " << trial << " lane " << j;
      (expected ? hits : misses) += 1;
    }
    // The 4 × 4 lane pairs of w and a record of random lanes (one of them a lane of w: identical volumes).
    WideBounds<BV> other;
    std::array<BV, 4> other_lane;
    for (int j = 0; j < 4; ++j) {
      other_lane[j] = j == trial % 4 ? lane[0] : random_dop();
      for (int i = 0; i < BV::num_axes; ++i)
        other.lo[i][j] = other_lane[j].min(i), other.hi[i][j] = other_lane[j].max(i);
    }
    const unsigned pairs = overlapping_lane_pairs_plain(w, other);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        EXPECT_EQ(bool(pairs >> (4 * i + j) & 1u), i < used && lane[i].overlaps(other_lane[j]))
            << "K=" << K << " trial " << trial << " lane pair " << i << ", " << j;
#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
    if (lane_pair_walk() == LanePairWalk::avx512) {
      EXPECT_EQ(lane_pairs_avx512_for_test(w, other), pairs) << "AVX-512 and plain lane-pair tests differ";
    }
    if (lane_pair_walk() != LanePairWalk::none) {
      EXPECT_EQ(lane_pairs_avx2_for_test(w, other), pairs) << "AVX2 and plain lane-pair tests differ";
    }
#endif
    alignas(16) float size[4], plain[4];
    lane_sizes(w, size);
    lane_sizes_plain(w, plain);
    for (int j = 0; j < used; ++j) {
      EXPECT_EQ(size[j], lane[j].size_measure());
      EXPECT_EQ(plain[j], lane[j].size_measure());
    }
  }
  EXPECT_GT(hits, 100u);
  EXPECT_GT(misses, 100u);
}

TEST(WideBvh, SimdLaneTestAgreesWithKDopOverlaps) {
  std::mt19937 rng(7);
  check_lane_test<6>(rng);
  check_lane_test<14>(rng);
  check_lane_test<18>(rng);
  check_lane_test<26>(rng);
}

TEST(WideBvh, TheLanePairWalkFollowsTheCpuAndCcdlabSimd) {
#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
  const auto targets = hwy::SupportedTargets();
  const LanePairWalk best = (targets & (HWY_AVX3 | HWY_AVX3_DL)) ? LanePairWalk::avx512
                            : (targets & HWY_AVX2)               ? LanePairWalk::avx2
                                                                 : LanePairWalk::none;
#else
  const LanePairWalk best = LanePairWalk::none;  // not compiled in (not x86-64, or not GCC/Clang)
#endif
  EXPECT_EQ(lane_pair_walk(), best);
  if (hwy::SupportedTargets() & HWY_AVX2) {
    limit_simd_target("avx2");
    EXPECT_EQ(lane_pair_walk(), LanePairWalk::avx2) << "CCDLAB_SIMD=avx2 takes the AVX2 walk";
    limit_simd_target("sse4");
    EXPECT_EQ(lane_pair_walk(), LanePairWalk::none) << "CCDLAB_SIMD=sse4 takes the SSE2 walk";
    hwy::SetSupportedTargetsForTest(0);
  }
  EXPECT_EQ(lane_pair_walk(), best);
}

}  // namespace
}  // namespace ccdlab
