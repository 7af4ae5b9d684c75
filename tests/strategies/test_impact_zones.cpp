// Rigid impact zones, ccd_contact's last resort: a sheet driven through another comes out of the rounds with no
// contact left, every zone moved rigidly and the free vertices' linear momentum kept; a zone that holds a
// scripted vertex moves with it; a zone holding two different scripted motions is counted as pinched, and each
// of its free vertices follows the nearest scripted vertex whose motion keeps it outside the obstacles' shapes.
#include <gtest/gtest.h>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/effects/impact_zones.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// Two 4×4 sheets, B 0.05 above A; one cloth body with self-collision (so A–B pairs are tested).
struct TwoSheets {
  MeshData data;
  std::unique_ptr<TriMesh> mesh;
  SimSetup setup;
  SimState state;
  std::size_t half = 0;

  TwoSheets() {
    MeshData a = test::grid(4, 4), b = test::grid(4, 4);
    for (Vec3& p : b.positions) p += Vec3(0.1, 0.05, 0.05);
    data = test::concat(a, b);
    half = a.positions.size();
    mesh = std::make_unique<TriMesh>(Index(data.positions.size()), data.faces);
    Body body;
    body.name = "sheets";
    body.vertex_end = Index(data.positions.size());
    body.face_end = Index(data.faces.size());
    setup.mesh = mesh.get();
    setup.bodies = {body};
    setup.rest = data.positions;
    setup.inv_mass.assign(data.positions.size(), 1.0);
    state.x = state.p = data.positions;
    state.v.assign(data.positions.size(), Vec3::Zero());
  }
  CcdPipeline crossing() const { return {*mesh, setup.bodies, contact_strategies(18, "sequential", 1, 0.0)}; }
  /// Sets the motion of sheet B (or A) to x → x + d, velocity d / dt.
  void drive(bool sheet_b, const Vec3& d, double dt) {
    for (std::size_t i = sheet_b ? half : 0; i < (sheet_b ? state.x.size() : half); ++i) {
      state.p[i] = state.x[i] + d;
      state.v[i] = d / dt;
    }
  }
};

TEST(ImpactZones, ASheetDrivenThroughAnotherEndsFreeOfContactsMovingRigidly) {
  TwoSheets s;
  const double dt = 0.01;
  s.drive(true, Vec3(0.02, 0, -0.1), dt);  // B goes through A
  for (std::size_t i = s.half; i < s.state.x.size(); ++i)  // and spins a little, so zones need angular momentum
    s.state.p[i] += 0.02 * Vec3(-(s.state.x[i].y() - 0.5), s.state.x[i].x() - 0.6, 0), s.state.v[i] = (s.state.p[i] - s.state.x[i]) / dt;
  CcdPipeline crossing = s.crossing();
  ASSERT_GT(crossing.step(s.state.x, s.state.p).contacts.size(), 0u) << "the motion crosses before";
  Vec3 momentum = Vec3::Zero();
  for (const Vec3& v : s.state.v) momentum += v;

  ImpactZones zones;
  const ImpactZones::Outcome out = zones.resolve(crossing, s.setup, s.state, dt, 64);
  EXPECT_EQ(out.left, 0u);
  EXPECT_EQ(crossing.step(s.state.x, s.state.p).contacts.size(), 0u);
  EXPECT_GT(zones.zones_moved, 0u);
  EXPECT_EQ(zones.pinched_zones, 0u);
  Vec3 after = Vec3::Zero();
  for (const Vec3& v : s.state.v) after += v;
  EXPECT_LT((after - momentum).norm(), 1e-9 * momentum.norm()) << "zones keep linear momentum";
  // Rigid: members of one zone keep their distances (every pair of every zone of two or more vertices).
  std::size_t pairs = 0;
  for (std::size_t a = 0; a < s.state.x.size(); ++a)
    for (std::size_t b = a + 1; b < s.state.x.size(); ++b) {
      if (zones.zone(Index(a)) != zones.zone(Index(b))) continue;
      ++pairs;
      EXPECT_NEAR((s.state.p[a] - s.state.p[b]).norm(), (s.state.x[a] - s.state.x[b]).norm(), 1e-12) << a << "–" << b;
    }
  EXPECT_GT(pairs, 0u);
}

TEST(ImpactZones, AZoneHoldingAScriptedVertexMovesWithIt) {
  TwoSheets s;
  const double dt = 0.01;
  for (std::size_t i = 0; i < s.half; ++i) s.setup.inv_mass[i] = 0;  // sheet A is scripted: it rises through B
  const Vec3 lift(0, 0, 0.1);
  s.drive(false, lift, dt);
  CcdPipeline crossing = s.crossing();
  ASSERT_GT(crossing.step(s.state.x, s.state.p).contacts.size(), 0u);
  ImpactZones zones;
  EXPECT_EQ(zones.resolve(crossing, s.setup, s.state, dt, 64).left, 0u);
  std::size_t carried = 0;
  for (std::size_t i = s.half; i < s.state.x.size(); ++i) {
    const Vec3 d = s.state.p[i] - s.state.x[i];
    EXPECT_TRUE(d.norm() == 0 || (d - lift).norm() < 1e-12) << "vertex " << i << " either rests or is carried";
    carried += d.norm() > 0;
  }
  EXPECT_GT(carried, 0u);
  EXPECT_EQ(zones.pinched_zones, 0u);
}

TEST(ImpactZones, TwoScriptedMotionsInOneZoneCountAsPinchedAndEachVertexFollowsTheNearest) {
  TwoSheets s;
  const double dt = 0.01;
  // Scripted vertices 0 at (0, 0, 0) and 4 at (1, 0, 0) move apart; free 1 (0.25, 0, 0) and 3 (0.75, 0, 0).
  s.setup.inv_mass[0] = s.setup.inv_mass[4] = 0;
  const Vec3 down(0, 0, -0.01), up(0, 0, 0.01);
  s.state.p[0] = s.state.x[0] + down;
  s.state.p[4] = s.state.x[4] + up;
  Contact c{};
  c.kind = ContactKind::vf;
  c.vertices = {0, 1, 3, 4};
  ImpactZones zones;
  zones.reset(s.state.x.size());
  EXPECT_EQ(zones.merge({c}), 1u);
  EXPECT_EQ(zones.merge({c}), 0u) << "merged already: another round cannot help";
  zones.move(s.setup, s.state, dt);
  EXPECT_EQ(zones.pinched_zones, 1u);
  EXPECT_EQ(s.state.p[1], s.state.x[1] + down) << "vertex 1 follows vertex 0, the nearer";
  EXPECT_EQ(s.state.p[3], s.state.x[3] + up) << "vertex 3 follows vertex 4";
  EXPECT_EQ(s.state.p[2], s.state.x[2]) << "vertex 2 is in no zone";

  // A sphere where vertex 0's motion would carry vertex 1: vertex 1 follows vertex 4 instead.
  SimObstacle ball;
  ball.shape = SimObstacle::Shape::sphere;
  ball.a = s.state.x[1] + down;
  ball.radius = 0.005;
  s.setup.obstacles.push_back(ball);
  s.state.p[1] = s.state.x[1];
  zones.move(s.setup, s.state, dt);
  EXPECT_EQ(s.state.p[1], s.state.x[1] + up) << "the nearer motion would carry vertex 1 into the sphere";
  EXPECT_EQ(s.state.p[3], s.state.x[3] + up);
}

}  // namespace
}  // namespace ccdlab
