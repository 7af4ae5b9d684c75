#include <gtest/gtest.h>

#include <set>

#include "framework/util/error.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

TEST(TriMesh, GridTopologyCounts) {
  MeshData g = test::grid(5, 4);
  TriMesh m(Index(g.positions.size()), g.faces);
  EXPECT_EQ(m.num_vertices(), 30);
  EXPECT_EQ(m.num_faces(), 40);
  // Euler characteristic of a disk: V − E + F = 1.
  EXPECT_EQ(m.num_vertices() - m.num_edges() + m.num_faces(), 1);
  EXPECT_EQ(m.num_components(), 1);
  // Each edge has 1 (boundary) or 2 faces; boundary edges of a 5×4 grid: 2·(5+4) = 18.
  int boundary = 0;
  for (Index e = 0; e < m.num_edges(); ++e) {
    auto faces = m.edge_faces(e);
    ASSERT_TRUE(faces.size() == 1 || faces.size() == 2);
    boundary += faces.size() == 1;
  }
  EXPECT_EQ(boundary, 18);
}

TEST(TriMesh, EdgesSortedByLargerThenSmallerVertex) {
  MeshData g = test::grid(3, 3);
  TriMesh m(Index(g.positions.size()), g.faces);
  for (Index e = 0; e < m.num_edges(); ++e) {
    EXPECT_LT(m.edge(e)[0], m.edge(e)[1]);
    if (e > 0) {
      auto prev = std::pair(m.edge(e - 1)[1], m.edge(e - 1)[0]);
      auto cur = std::pair(m.edge(e)[1], m.edge(e)[0]);
      EXPECT_LT(prev, cur);
    }
  }
}

TEST(TriMesh, AdjacencyIsConsistent) {
  MeshData g = test::grid(4, 3);
  TriMesh m(Index(g.positions.size()), g.faces);
  for (Index f = 0; f < m.num_faces(); ++f)
    for (int j = 0; j < 3; ++j) {
      Index e = m.face_edges(f)[j];
      std::set<Index> ends{m.face(f)[j], m.face(f)[(j + 1) % 3]};
      EXPECT_EQ(ends, (std::set<Index>{m.edge(e)[0], m.edge(e)[1]}));
      auto ef = m.edge_faces(e);
      EXPECT_NE(std::find(ef.begin(), ef.end(), f), ef.end());
      auto vf = m.vertex_faces(m.face(f)[j]);
      EXPECT_NE(std::find(vf.begin(), vf.end(), f), vf.end());
      EXPECT_EQ(m.find_edge(m.edge(e)[1], m.edge(e)[0]), e);
    }
  EXPECT_TRUE(m.faces_adjacent(0, 1));
  EXPECT_FALSE(m.faces_adjacent(0, m.num_faces() - 1));
}

TEST(TriMesh, ComponentsOfDisjointPieces) {
  MeshData both = test::concat(test::grid(2, 2), test::grid(3, 1));
  TriMesh m(Index(both.positions.size()), both.faces);
  EXPECT_EQ(m.num_components(), 2);
  EXPECT_EQ(m.face_components().front(), 0);
  EXPECT_EQ(m.face_components().back(), 1);
}

TEST(TriMesh, RejectsBadFacesNamingThem) {
  auto message = [](Index nv, std::vector<Face> faces) {
    try {
      TriMesh m(nv, std::move(faces));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(3, {{0, 1, 3}}), "face 0: vertex index 3 out of range [0, 3)");
  EXPECT_EQ(message(4, {{0, 1, 2}, {1, 1, 3}}), "face 1: degenerate, repeats a vertex (1 1 3)");
  EXPECT_EQ(message(4, {{0, 1, 2}, {1, 3, 2}, {2, 0, 1}}), "face 2: duplicate of face 0 (vertices 0 1 2)");
}

}  // namespace
}  // namespace ccdlab
