#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strategies/builders/median_builder.hpp"
#include "strategies/builders/sah_builder.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

std::vector<Box3> face_boxes(const MeshData& m) {
  std::vector<Box3> boxes(m.faces.size());
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    for (Index v : m.faces[f]) boxes[f].grow(m.positions[v]);
  return boxes;
}

int depth(const BvhTopology& bvh, Index node) {
  const BvhNode& n = bvh.nodes[node];
  return n.is_leaf() ? 0 : 1 + std::max(depth(bvh, n.left), depth(bvh, n.right));
}

/// Every face of a crumpled grid, with its box.
struct FaceSet {
  std::vector<Index> faces;
  std::vector<Box3> boxes;
};
FaceSet crumpled_grid(int nx, int ny, unsigned seed) {
  std::mt19937 rng(seed);
  MeshData g = test::grid(nx, ny);
  g.positions = test::crumple(g.positions, rng, 0.01);
  FaceSet set{std::vector<Index>(g.faces.size()), face_boxes(g)};
  for (std::size_t i = 0; i < set.faces.size(); ++i) set.faces[i] = Index(i);
  return set;
}

TEST(Builders, ProduceValidPreOrderTreesWithOneFacePerLeaf) {
  const auto [faces, boxes] = crumpled_grid(17, 9, 3);
  MedianBuilder median;
  SahBuilder sah;
  for (const HierarchyBuilder* b : std::initializer_list<const HierarchyBuilder*>{&median, &sah}) {
    BvhTopology bvh = b->build(faces, boxes);
    EXPECT_NO_THROW(validate_bvh(bvh, faces)) << b->name();
    EXPECT_EQ(bvh.leaf_count[0], Index(faces.size())) << b->name();
  }
  // The median split is balanced.
  EXPECT_EQ(depth(median.build(faces, boxes), 0), int(std::ceil(std::log2(double(faces.size())))));
}

TEST(Builders, BuildTheSameTreeOnAnyNumberOfThreads) {
  // 2·60·60 = 7,200 faces: several sub-tree tasks below the top splits (build_top_down).
  const auto [faces, boxes] = crumpled_grid(61, 61, 4);
  MedianBuilder median;
  SahBuilder sah;
  for (const HierarchyBuilder* b : std::initializer_list<const HierarchyBuilder*>{&median, &sah}) {
    const BvhTopology one = b->build(faces, boxes);
    for (int threads : {2, 3}) {
      PhaseTrace trace;
      const BvhTopology many = b->build(faces, boxes, {threads, &trace});
      EXPECT_NO_THROW(validate_bvh(many, faces)) << b->name();
      ASSERT_EQ(many.size(), one.size()) << b->name();
      for (Index i = 0; i < one.size(); ++i) {
        const BvhNode &x = one.nodes[i], &y = many.nodes[i];
        ASSERT_TRUE(x.left == y.left && x.right == y.right && x.parent == y.parent && x.face == y.face)
            << b->name() << " node " << i << " threads " << threads;
      }
      EXPECT_EQ(many.leaf_count, one.leaf_count) << b->name();
      EXPECT_GT(trace.task_ms.size(), 2u) << b->name();  // the sub-trees were tasks
    }
  }
}

TEST(Builders, HandleSubsetsCoincidentCentroidsAndSingleFaces) {
  MeshData g = test::grid(4, 4);
  std::vector<Index> subset{3, 7, 8, 20, 31};
  std::vector<Box3> boxes(subset.size());
  for (auto& b : boxes) b.grow(Vec3(1, 1, 1));  // all centroids equal
  for (const HierarchyBuilder* b : std::initializer_list<const HierarchyBuilder*>{new MedianBuilder, new SahBuilder}) {
    EXPECT_NO_THROW(validate_bvh(b->build(subset, boxes), subset)) << b->name();
    std::vector<Index> one{5};
    std::vector<Box3> one_box(1);
    one_box[0].grow(Vec3(0, 0, 0));
    BvhTopology t = b->build(one, one_box);
    ASSERT_EQ(t.size(), 1);
    EXPECT_EQ(t.nodes[0].face, 5);
    delete b;
  }
}

TEST(Refit, ParentsContainChildren) {
  MeshData g = test::grid(6, 6);
  std::vector<Index> faces(g.faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) faces[i] = Index(i);
  BvhTopology bvh = MedianBuilder().build(faces, face_boxes(g));
  BvArray<KDop<14>> bvs;
  refit(bvh, bvs, [&](Index f) {
    KDop<14> b;
    for (Index v : g.faces[f]) b.grow(g.positions[v]);
    return b;
  });
  for (Index i = 1; i < bvh.size(); ++i)
    for (int a = 0; a < 7; ++a) {
      const auto& parent = bvs[bvh.nodes[i].parent];
      EXPECT_LE(parent.min(a), bvs[i].min(a));
      EXPECT_GE(parent.max(a), bvs[i].max(a));
    }
}

}  // namespace
}  // namespace ccdlab
