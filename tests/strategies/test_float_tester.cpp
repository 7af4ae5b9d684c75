// The `float` tester on cases with known answers. It is not conservative: the accuracy ladder (a later issue)
// counts its misses on hard sets; here it must get the clear-cut and the classic degenerate cases right, and
// give the same answer whatever the scale or position of the query.
#include <gtest/gtest.h>

#include "strategies/testers/float_tester.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

VertexFaceQuery vf(Vec3 v0, Vec3 v1, Vec3 a, Vec3 b, Vec3 c) { return {v0, a, b, c, v1, a, b, c}; }

VertexFaceQuery transform(VertexFaceQuery q, double s, const Vec3& t) {
  for (Vec3* p : {&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1}) *p = s * *p + t;
  return q;
}
EdgeEdgeQuery transform(EdgeEdgeQuery q, double s, const Vec3& t) {
  for (Vec3* p : {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1}) *p = s * *p + t;
  return q;
}

const Vec3 A(0, 0, 0), B(1, 0, 0), C(0, 1, 0);

TEST(FloatTester, VertexThroughFaceHitsAtTheCrossingTime) {
  FloatTester t;
  CcdHit h = t.vertex_face(vf(Vec3(0.25, 0.25, 1), Vec3(0.25, 0.25, -1), A, B, C));
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.toi, 0.5, 1e-12);
  EXPECT_NEAR(h.coords[0], 0.25, 1e-9);
  EXPECT_NEAR(h.coords[1], 0.25, 1e-9);
  // Non-uniform speed along the way: crossing at z = 0 when 1 - 4t = 0.
  h = t.vertex_face(vf(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -3), A, B, C));
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.toi, 0.25, 1e-12);
}

TEST(FloatTester, VertexPassingBesideTheFaceMisses) {
  FloatTester t;
  EXPECT_FALSE(t.vertex_face(vf(Vec3(0.8, 0.8, 1), Vec3(0.8, 0.8, -1), A, B, C)).hit);  // outside the hypotenuse
  EXPECT_FALSE(t.vertex_face(vf(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0.1), A, B, C)).hit);  // stops short
}

TEST(FloatTester, ThicknessTurnsANearMissIntoContact) {
  const auto q = vf(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0.05), A, B, C);
  EXPECT_FALSE(FloatTester().vertex_face(q).hit);
  CcdHit h = FloatTester({0.1}).vertex_face(q);
  EXPECT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.toi, 1.0);
}

TEST(FloatTester, ContactAtStartAndEndOfTheStep) {
  FloatTester t;
  CcdHit h0 = t.vertex_face(vf(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, 1), A, B, C));
  ASSERT_TRUE(h0.hit);
  EXPECT_EQ(h0.toi, 0.0);
  CcdHit h1 = t.vertex_face(vf(Vec3(0.2, 0.2, 1), Vec3(0.3, 0.1, 0), A, B, C));
  ASSERT_TRUE(h1.hit);
  EXPECT_EQ(h1.toi, 1.0);
}

TEST(FloatTester, CoplanarMotionSlidingIntoTheFace) {
  // The vertex moves inside the triangle's plane from outside to inside: f(t) ≡ 0.
  FloatTester t;
  CcdHit h = t.vertex_face(vf(Vec3(-1, 0.25, 0), Vec3(1, 0.25, 0), A, B, C));
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.toi, 0.5, 1e-9);  // enters through the edge x = 0
  EXPECT_FALSE(t.vertex_face(vf(Vec3(-1, -0.5, 0), Vec3(1, -0.5, 0), A, B, C)).hit);
}

TEST(FloatTester, MovingFaceCatchesAStillVertex) {
  // The face tilts up under a still vertex: contact when the plane height under it reaches 0.1.
  FloatTester t;
  VertexFaceQuery q{Vec3(0.2, 0.2, 0.1), A, B, C, Vec3(0.2, 0.2, 0.1), Vec3(0, 0, 0.3), Vec3(1, 0, 0.3), Vec3(0, 1, -0.3)};
  CcdHit h = t.vertex_face(q);
  ASSERT_TRUE(h.hit);
  // f(t) crosses at the time the plane height under (0.2, 0.2) equals 0.1.
  double z_under = (1 - 0.2 - 0.2) * 0.3 + 0.2 * 0.3 + 0.2 * -0.3;  // at t = 1
  EXPECT_NEAR(h.toi, 0.1 / z_under, 1e-9);
}

TEST(FloatTester, CrossingEdgesHit) {
  FloatTester t;
  EdgeEdgeQuery q{Vec3(-1, 0, 1), Vec3(1, 0, 1), Vec3(0, -1, 0), Vec3(0, 1, 0),
                  Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, -1, 0), Vec3(0, 1, 0)};
  CcdHit h = t.edge_edge(q);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.toi, 0.5, 1e-12);
  EXPECT_NEAR(h.coords[0], 0.5, 1e-9);
  EXPECT_NEAR(h.coords[1], 0.5, 1e-9);
  // Shifted so the edges pass each other without touching.
  EdgeEdgeQuery miss = q;
  for (Vec3* p : {&miss.eb0_t0, &miss.eb1_t0, &miss.eb0_t1, &miss.eb1_t1}) *p += Vec3(2, 0, 0);
  EXPECT_FALSE(t.edge_edge(miss).hit);
}

TEST(FloatTester, ParallelEdgesMovingIntoOverlap) {
  // Parallel edges in one plane, sliding sideways onto each other (coplanar, parallel: doubly degenerate).
  FloatTester t;
  EdgeEdgeQuery q{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(1.5, 1, 0),
                  Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 0), Vec3(1.5, -1, 0)};
  CcdHit h = t.edge_edge(q);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.toi, 0.5, 1e-9);
  // Collinear, disjoint, not moving: no contact.
  EdgeEdgeQuery apart{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0),
                      Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)};
  EXPECT_FALSE(t.edge_edge(apart).hit);
}

TEST(FloatTester, AnswersDoNotDependOnScaleOrPosition) {
  FloatTester t;
  const std::vector<VertexFaceQuery> vfs{vf(Vec3(0.25, 0.25, 1), Vec3(0.25, 0.25, -1), A, B, C),
                                         vf(Vec3(0.8, 0.8, 1), Vec3(0.8, 0.8, -1), A, B, C),
                                         vf(Vec3(-1, 0.25, 0), Vec3(1, 0.25, 0), A, B, C),
                                         vf(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0.01), A, B, C)};
  const EdgeEdgeQuery ee{Vec3(-1, 0, 1), Vec3(1, 0, 1), Vec3(0, -1, 0), Vec3(0, 1, 0),
                         Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, -1, 0), Vec3(0, 1, 0)};
  for (double s : {1e-3, 1e-2, 1.0, 1e2, 1e3})
    for (const Vec3& shift : {Vec3(0, 0, 0), Vec3(1e3, -2e3, 5e2)}) {
      for (std::size_t i = 0; i < vfs.size(); ++i) {
        CcdHit ref = t.vertex_face(vfs[i]);
        CcdHit h = t.vertex_face(transform(vfs[i], s, shift * s));
        EXPECT_EQ(h.hit, ref.hit) << "vf case " << i << " scale " << s << " shift " << shift.transpose();
        if (h.hit) {
          EXPECT_NEAR(h.toi, ref.toi, 1e-6);
        }
      }
      CcdHit h = t.edge_edge(transform(ee, s, shift * s));
      EXPECT_TRUE(h.hit) << "ee scale " << s;
      EXPECT_NEAR(h.toi, 0.5, 1e-6);
    }
}

}  // namespace
}  // namespace ccdlab
