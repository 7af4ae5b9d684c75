// The proximity query's elementary test (framework/primitive/static_distance.hpp): its decision "distance < d̂"
// against CGAL's exact squared distances in rationals (an independent implementation), on random pairs placed at
// d̂ to within rounding; the degenerate configurations the issue names; and the closest-feature types.
#include <gtest/gtest.h>

#include <CGAL/Gmpq.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/squared_distance_3.h>

#include <cmath>
#include <random>

#include "framework/primitive/static_distance.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using K = CGAL::Simple_cartesian<CGAL::Gmpq>;

K::Point_3 exact(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

/// The exact squared distances, by CGAL (non-degenerate faces; segments may be point-like).
CGAL::Gmpq exact_vf(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return CGAL::squared_distance(exact(p), K::Triangle_3(exact(a), exact(b), exact(c)));
}
CGAL::Gmpq exact_ee(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  return CGAL::squared_distance(K::Segment_3(exact(a0), exact(a1)), K::Segment_3(exact(b0), exact(b1)));
}
bool exactly_closer(const CGAL::Gmpq& d2, double dhat) { return d2 < CGAL::Gmpq(dhat) * CGAL::Gmpq(dhat); }

Vec3 random_point(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

TEST(StaticDistance, DecidesAsExactRationalsOnPairsAtTheThreshold) {
  // d̂ is each pair's own double distance, nudged by a few ulps or a relative 1e-12 either way: the decision
  // then rests on the last bits, where only an exact one is right every time.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> nudge(-3, 3);
  std::uniform_real_distribution<double> offset(-1e3, 1e3);
  int vf_closer = 0, ee_closer = 0, in_rationals = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const Vec3 at = i % 4 == 0 ? Vec3(offset(rng), offset(rng), offset(rng)) : Vec3::Zero();  // far from the origin too
    const Vec3 p = at + random_point(rng, 1), a = at + random_point(rng, 1), b = at + random_point(rng, 1),
               c = at + random_point(rng, 1);
    double dhat = closest_vertex_face(p, a, b, c).distance;
    for (int k = nudge(rng); k != 0; k += k > 0 ? -1 : 1) dhat = std::nextafter(dhat, k > 0 ? 1e300 : 0.0);
    if (i % 3 == 0) dhat *= 1 + 1e-12 * nudge(rng);
    const DistanceVerdict vf = vertex_face_closer(p, a, b, c, dhat);
    ASSERT_EQ(vf.closer, exactly_closer(exact_vf(p, a, b, c), dhat)) << "VF pair " << i;
    double dhat_ee = closest_edge_edge(p, a, b, c).distance;
    for (int k = nudge(rng); k != 0; k += k > 0 ? -1 : 1) dhat_ee = std::nextafter(dhat_ee, k > 0 ? 1e300 : 0.0);
    const DistanceVerdict ee = edge_edge_closer(p, a, b, c, dhat_ee);
    ASSERT_EQ(ee.closer, exactly_closer(exact_ee(p, a, b, c), dhat_ee)) << "EE pair " << i;
    vf_closer += vf.closer, ee_closer += ee.closer, in_rationals += vf.in_rationals + ee.in_rationals;
  }
  // Both answers occur, and the intervals left many of these borderline pairs to the rationals.
  EXPECT_GT(vf_closer, n / 5);
  EXPECT_LT(vf_closer, 4 * n / 5);
  EXPECT_GT(ee_closer, n / 5);
  EXPECT_LT(ee_closer, 4 * n / 5);
  EXPECT_GT(in_rationals, n / 2);
}

TEST(StaticDistance, DecidesClearPairsWithIntervalsAlone) {
  // Pairs whose distance is not within a relative 1e-6 of d̂: intervals decide them all, as exact rationals would.
  std::mt19937 rng(9);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = random_point(rng, 1), a = random_point(rng, 1), b = random_point(rng, 1), c = random_point(rng, 1);
    const double d = closest_vertex_face(p, a, b, c).distance, dhat = d * (i % 2 ? 1 + 1e-6 : 1 - 1e-6);
    const DistanceVerdict vf = vertex_face_closer(p, a, b, c, dhat);
    EXPECT_EQ(vf.closer, i % 2 == 1) << i;
    EXPECT_FALSE(vf.in_rationals) << i;
    const double e = closest_edge_edge(p, a, b, c).distance, ehat = e * (i % 2 ? 1 + 1e-6 : 1 - 1e-6);
    const DistanceVerdict ee = edge_edge_closer(p, a, b, c, ehat);
    EXPECT_EQ(ee.closer, i % 2 == 1) << i;
    EXPECT_FALSE(ee.in_rationals) << i;
  }
}

TEST(StaticDistance, DistanceExactlyDhatIsNotCloser) {
  const double dhat = 0.1;  // not a binary fraction: the plane's distance is exactly this double, not 1/10
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_FALSE(vertex_face_closer({0.25, 0.25, dhat}, a, b, c, dhat).closer);
  EXPECT_TRUE(vertex_face_closer({0.25, 0.25, std::nextafter(dhat, 0.0)}, a, b, c, dhat).closer);
  EXPECT_FALSE(vertex_face_closer({0.25, 0.25, -dhat}, a, b, c, dhat).closer);  // behind the face as well
  // Beside an edge, beside a corner.
  EXPECT_FALSE(vertex_face_closer({0.5, -dhat, 0}, a, b, c, dhat).closer);
  EXPECT_TRUE(vertex_face_closer({0.5, -std::nextafter(dhat, 0.0), 0}, a, b, c, dhat).closer);
  EXPECT_FALSE(vertex_face_closer({-dhat, 0, 0}, a, b, c, dhat).closer);
  // Parallel edges, one above the other's middle, at exactly d̂.
  EXPECT_FALSE(edge_edge_closer(a, b, {0.2, 0, dhat}, {0.8, 0, dhat}, dhat).closer);
  EXPECT_TRUE(edge_edge_closer(a, b, {0.2, 0, std::nextafter(dhat, 0.0)}, {0.8, 0, std::nextafter(dhat, 0.0)}, dhat).closer);
  // Crossing edges at exactly d̂.
  EXPECT_FALSE(edge_edge_closer(a, b, {0.5, -1, dhat}, {0.5, 1, dhat}, dhat).closer);
  EXPECT_TRUE(edge_edge_closer(a, b, {0.5, -1, 0.09}, {0.5, 1, 0.09}, dhat).closer);
}

TEST(StaticDistance, DegenerateAndCoplanarConfigurations) {
  const double dhat = 0.1;
  // A face of zero area (collinear corners) and one that is a point: the distance to their segments, to the point.
  EXPECT_TRUE(vertex_face_closer({0.5, 0.05, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, dhat).closer);
  EXPECT_FALSE(vertex_face_closer({0.5, 0.1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, dhat).closer);
  EXPECT_FALSE(vertex_face_closer({0.5, 0.5, 0.0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, dhat).closer);
  EXPECT_TRUE(vertex_face_closer({0.3, 0.3, 0.05}, {0.3, 0.3, 0}, {0.3, 0.3, 0}, {0.3, 0.3, 0}, dhat).closer);
  EXPECT_FALSE(vertex_face_closer({0.3, 0.3, 0.1}, {0.3, 0.3, 0}, {0.3, 0.3, 0}, {0.3, 0.3, 0}, dhat).closer);
  // A vertex on an edge, and a vertex in the face's plane beside it (coplanar, 0.05 from edge e0).
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(vertex_face_closer({0.5, 0, 0}, a, b, c, 1e-300).closer);
  EXPECT_TRUE(vertex_face_closer({0.5, -0.05, 0}, a, b, c, dhat).closer);
  EXPECT_FALSE(vertex_face_closer({0.5, -0.2, 0}, a, b, c, dhat).closer);
  // Point-like edges, collinear edges with a gap, edges crossing in one plane (distance 0).
  EXPECT_TRUE(edge_edge_closer({0.5, 0.05, 0}, {0.5, 0.05, 0}, a, b, dhat).closer);
  EXPECT_FALSE(edge_edge_closer({0.5, 0.1, 0}, {0.5, 0.1, 0}, a, b, dhat).closer);
  EXPECT_TRUE(edge_edge_closer(a, b, {1.05, 0, 0}, {2, 0, 0}, dhat).closer);
  EXPECT_FALSE(edge_edge_closer(a, b, {1.1, 0, 0}, {2, 0, 0}, dhat).closer);
  EXPECT_TRUE(edge_edge_closer(a, b, {0.5, -1, 0}, {0.5, 1, 0}, 1e-300).closer);
}

TEST(StaticDistance, NamesTheClosestFeatures) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(closest_vertex_face({0.25, 0.25, 0.1}, a, b, c).type, DistanceType::p_t);
  EXPECT_EQ(closest_vertex_face({-0.1, -0.1, 0}, a, b, c).type, DistanceType::p_t0);
  EXPECT_EQ(closest_vertex_face({1.1, -0.1, 0}, a, b, c).type, DistanceType::p_t1);
  EXPECT_EQ(closest_vertex_face({0, 1.2, 0.1}, a, b, c).type, DistanceType::p_t2);
  EXPECT_EQ(closest_vertex_face({0.5, -0.1, 0.1}, a, b, c).type, DistanceType::p_e0);
  EXPECT_EQ(closest_vertex_face({0.6, 0.6, 0.1}, a, b, c).type, DistanceType::p_e1);
  EXPECT_EQ(closest_vertex_face({-0.1, 0.5, 0.1}, a, b, c).type, DistanceType::p_e2);
  const ClosestFeatures inside = closest_vertex_face({0.25, 0.5, 0.1}, a, b, c);
  EXPECT_NEAR(inside.distance, 0.1, 1e-15);
  EXPECT_NEAR(inside.coords[0], 0.25, 1e-15);
  EXPECT_NEAR(inside.coords[1], 0.5, 1e-15);

  EXPECT_EQ(closest_edge_edge(a, b, {0.5, -1, 0.1}, {0.5, 1, 0.1}).type, DistanceType::ea_eb);
  EXPECT_EQ(closest_edge_edge(a, b, {-0.5, -1, 0.1}, {-0.5, 1, 0.1}).type, DistanceType::ea0_eb);
  EXPECT_EQ(closest_edge_edge(a, b, {1.5, 0, 0.1}, {2, 0, 0.1}).type, DistanceType::ea1_eb0);
  EXPECT_EQ(closest_edge_edge(a, b, {2, 0, 0.1}, {1.5, 0, 0.1}).type, DistanceType::ea1_eb1);
  EXPECT_EQ(closest_edge_edge(a, b, {0.5, 0.1, 0}, {0.5, 1, 0}).type, DistanceType::ea_eb0);
  EXPECT_EQ(closest_edge_edge(a, b, {0.5, 1, 0}, {0.5, 0.1, 0}).type, DistanceType::ea_eb1);
  for (const std::string& name : kDistanceTypes.names()) EXPECT_EQ(to_string(*kDistanceTypes.find(name)), name);
}

TEST(StaticDistance, TesterReportsHitsAtTheFirstFrameWithItsReach) {
  const StaticDistanceTester t(0.1);
  EXPECT_EQ(t.thickness(), 0.1);
  ASSERT_TRUE(t.cull_reach());
  EXPECT_EQ(t.cull_reach()->abs, 0.1);
  VertexFaceQuery q{{0.25, 0.25, 0.05}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25, 0.25, 0.05}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_TRUE(t.vertex_face(q).hit);
  q.v_t0.z() = 0.2, q.v_t1.z() = 0.2;
  EXPECT_FALSE(t.vertex_face(q).hit);
  EXPECT_THROW(StaticDistanceTester(0), Error);
  EXPECT_THROW(StaticDistanceTester(std::nan("")), Error);
  EXPECT_THROW(StaticDistanceTester(-1), Error);
}

}  // namespace
}  // namespace ccdlab
