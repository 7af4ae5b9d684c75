// The polyhedron of a k-DOP (what `ccdlab export` draws) is a closed convex solid: Euler characteristic 2,
// faces on the k-DOP's planes and oriented outward, every vertex inside every slab, the bounded points inside
// it, and no more faces than slabs (a 6-DOP is a box).
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "framework/geometry/kdop_polyhedron.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

template <int K>
void check_solid(const KDop<K>& bv, const std::vector<Vec3>& points, std::size_t min_faces) {
  const Polyhedron p = kdop_polyhedron(bv);
  ASSERT_GE(p.faces.size(), min_faces);
  ASSERT_LE(p.faces.size(), std::size_t(K));
  std::map<std::pair<int, int>, int> edges;  // directed edge → uses: each once, and its reverse once
  for (const auto& face : p.faces) {
    ASSERT_GE(face.size(), 3u);
    Vec3 newell = Vec3::Zero(), centre = Vec3::Zero();
    for (std::size_t i = 0; i < face.size(); ++i) {
      const Vec3& a = p.vertices[std::size_t(face[i])];
      const Vec3& b = p.vertices[std::size_t(face[(i + 1) % face.size()])];
      newell += a.cross(b);
      centre += a;
      ++edges[{face[i], face[(i + 1) % face.size()]}];
    }
    centre /= double(face.size());
    // Outward: the face normal points away from the solid's centre.
    Vec3 solid_centre = Vec3::Zero();
    for (const Vec3& v : p.vertices) solid_centre += v;
    solid_centre /= double(p.vertices.size());
    EXPECT_GT(newell.dot(centre - solid_centre), 0);
  }
  for (const auto& [e, uses] : edges) {
    EXPECT_EQ(uses, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << "a closed surface uses every edge once each way";
  }
  const long chi = long(p.vertices.size()) - long(edges.size() / 2) + long(p.faces.size());
  EXPECT_EQ(chi, 2);
  for (const Vec3& v : p.vertices)
    for (int i = 0; i < K / 2; ++i) {
      const auto& d = KDop<K>::axes[std::size_t(i)];
      const double s = d[0] * v.x() + d[1] * v.y() + d[2] * v.z();
      EXPECT_GE(s, double(bv.min(i)) - 1e-6);
      EXPECT_LE(s, double(bv.max(i)) + 1e-6);
    }
  for (const Vec3& q : points) EXPECT_TRUE(bv.contains(q));
}

/// A slab whose extreme point is a vertex of the others gives no face, so a random cloud's k-DOP has between
/// 6 (its box faces always touch it in a face here) and K faces.
template <int K>
void check_random_clouds() {
  std::mt19937 rng(K);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> pts;
    KDop<K> bv;
    for (int i = 0; i < 40; ++i) {
      pts.emplace_back(3 * u(rng) + 10, u(rng) - 5, 0.5 * u(rng));
      bv.grow(pts.back());
    }
    check_solid(bv, pts, 6);
  }
}

TEST(KDopPolyhedron, SixDopIsABox) {
  KDop<6> box;
  box.grow(Vec3(0, 0, 0));
  box.grow(Vec3(1, 2, 3));
  const Polyhedron p = kdop_polyhedron(box);
  EXPECT_EQ(p.vertices.size(), 8u);
  check_solid(box, {}, 6);
}

TEST(KDopPolyhedron, ClosedConvexOutwardSolidsForEveryK) {
  check_random_clouds<6>();
  check_random_clouds<14>();
  check_random_clouds<18>();
  check_random_clouds<26>();
}

TEST(KDopPolyhedron, EmptyKDopHasNoSolid) {
  const Polyhedron p = kdop_polyhedron(KDop<18>{});
  EXPECT_TRUE(p.vertices.empty());
  EXPECT_TRUE(p.faces.empty());
}

}  // namespace
}  // namespace ccdlab
