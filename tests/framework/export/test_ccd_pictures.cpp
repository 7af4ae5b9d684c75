// The pictures of `ccdlab export`: front changes are classified against the last front (kept, sprouted below
// it, pruned above it), per-face contact counts follow the features' incident triangles, and a BVH level holds
// the polyhedra of exactly the nodes at that depth.
#include <gtest/gtest.h>

#include "framework/export/ccd_pictures.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// A 4-leaf balanced BVH in pre-order: 0 → (1 → 2, 3), (4 → 5, 6).
BvhTopology four_leaves() {
  BvhTopology t;
  t.nodes = {{1, 4, -1, -1}, {2, 3, 0, -1}, {-1, -1, 1, 0}, {-1, -1, 1, 1},
             {5, 6, 0, -1},  {-1, -1, 4, 2}, {-1, -1, 4, 3}};
  return t;
}

TEST(ExportFront, KeptSproutedAndPrunedAgainstTheLastFront) {
  const BvhTopology a = four_leaves(), b = four_leaves();
  const std::vector<FrontNode> previous{{1, 4, 0}, {5, 6, 0}};
  const std::vector<FrontNode> current{{1, 4, 0},   // kept
                                       {1, 5, 0},   // below (1, 4): sprouted
                                       {1, 6, 0},   // below (1, 4): sprouted
                                       {4, 4, 0}};  // above (5, 6): pruned
  const auto change = classify_front(a, b, previous, current);
  ASSERT_EQ(change.size(), 4u);
  EXPECT_EQ(change[0], FrontChange::kept);
  EXPECT_EQ(change[1], FrontChange::sprouted);
  EXPECT_EQ(change[2], FrontChange::sprouted);
  EXPECT_EQ(change[3], FrontChange::pruned);
  for (FrontChange c : classify_front(a, b, {}, current)) EXPECT_EQ(c, FrontChange::sprouted) << "first step: from the root";
}

TEST(ExportMesh, ContactCountsFollowTheFeaturesIncidentTriangles) {
  const MeshData g = test::grid(3, 3);  // 18 triangles
  const TriMesh mesh(g.positions.size(), g.faces);
  // A VF contact: vertex 0 (a corner) against face 10; an EE contact between two interior edges.
  Contact vf{ContactKind::vf, 0, 10, {0, mesh.face(10)[0], mesh.face(10)[1], mesh.face(10)[2]}, 0.5, {0.2, 0.3}};
  const Index e0 = 0, e1 = mesh.num_edges() - 1;
  Contact ee{ContactKind::ee, e0, e1,
             {mesh.edge(e0)[0], mesh.edge(e0)[1], mesh.edge(e1)[0], mesh.edge(e1)[1]}, 0.25, {0.5, 0.5}};
  const std::vector<int> counts = contacts_per_face(mesh, {vf, ee});
  std::vector<int> expected(std::size_t(mesh.num_faces()), 0);
  std::vector<Index> vf_faces{10};
  for (Index f : mesh.vertex_faces(0)) vf_faces.push_back(f);
  std::sort(vf_faces.begin(), vf_faces.end());
  vf_faces.erase(std::unique(vf_faces.begin(), vf_faces.end()), vf_faces.end());
  for (Index f : vf_faces) ++expected[std::size_t(f)];
  std::vector<Index> ee_faces;
  for (Index e : {e0, e1})
    for (Index f : mesh.edge_faces(e)) ee_faces.push_back(f);
  std::sort(ee_faces.begin(), ee_faces.end());
  ee_faces.erase(std::unique(ee_faces.begin(), ee_faces.end()), ee_faces.end());
  for (Index f : ee_faces) ++expected[std::size_t(f)];
  EXPECT_EQ(counts, expected);

  Positions x0(std::size_t(mesh.num_vertices())), x1;
  for (Index v = 0; v < mesh.num_vertices(); ++v) x0[std::size_t(v)] = Vec3(v % 4, v / 4, 0);
  x1 = x0;
  for (Vec3& p : x1) p.z() += 1;
  const VtkGrid contacts = contacts_grid({vf, ee}, x0, x1);
  EXPECT_EQ(contacts.num_cells(), 2u + 3u);  // VF: point + face; EE: point + two edges
  const VtkGrid m = mesh_grid(mesh, {Body{"sheet", BodyKind::cloth, true, 0, mesh.num_vertices(), 0, mesh.num_faces()}},
                              x0, x1, counts);
  EXPECT_EQ(m.num_cells(), std::size_t(mesh.num_faces()));
  EXPECT_EQ(m.num_points(), std::size_t(mesh.num_vertices()));
}

TEST(ExportBvh, ALevelHoldsThePolyhedraOfTheNodesAtThatDepth) {
  const BvhTopology t = four_leaves();
  BvArray<KDop<6>> boxes(t.nodes.size());  // constructs nothing: each box starts empty below
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    boxes[i] = KDop<6>();
    boxes[i].grow(Vec3(double(i), 0, 0));
    boxes[i].grow(Vec3(double(i) + 0.5, 1, 1));
  }
  const AnyBvs bvs = boxes;
  EXPECT_EQ(node_depths(t), (std::vector<int>{0, 1, 2, 2, 1, 2, 2}));
  EXPECT_EQ(bvh_level_grid(t, bvs, 0, 0).num_cells(), 6u);
  EXPECT_EQ(bvh_level_grid(t, bvs, 1, 0).num_cells(), 12u);
  EXPECT_EQ(bvh_level_grid(t, bvs, 2, 0).num_cells(), 24u);
  EXPECT_EQ(bvh_level_grid(t, bvs, 3, 0).num_cells(), 0u);
}

}  // namespace
}  // namespace ccdlab
