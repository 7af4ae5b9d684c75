// Inelastic projection, ccd_contact's response to every crossing at once: a cloth strip in the corner of a
// rising floor and an advancing wall (one obstacle moving two ways: a knee's thigh and shin) comes out free of
// contacts — the case rigid impact zones can only count as pinched — with the scripted vertices where their
// motion puts them and a vertex in no contact untouched. And the impact zones' last escalation: whole cloth
// bodies join the zone of the contacts that touch them.
#include <gtest/gtest.h>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/effects/impact_zones.hpp"
#include "strategies/effects/inelastic_projection.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// Body 0, cloth: a strip rising out of the corner, its bottom edge 0.01 from both floor and wall, and a loose
/// triangle far away. Body 1, obstacle: the floor y = 0 and the wall x = 0, 2×2 grids each.
struct Corner {
  MeshData data;
  std::unique_ptr<TriMesh> mesh;
  SimSetup setup;
  SimState state;
  std::size_t cloth_vertices = 0;
  static constexpr double dt = 0.01, gap = 1e-4, push = 0.02;

  Corner() {
    MeshData strip = test::grid(1, 1);  // vertices 0, 2: the bottom edge; 1, 3: the top edge
    for (Vec3& p : strip.positions) p = Vec3(0.01 + 0.2 * p.x(), 0.01 + 0.2 * p.x(), 0.4 + 0.2 * p.y());
    MeshData loose;
    loose.positions = {Vec3(0.8, 0.8, 0.1), Vec3(0.9, 0.8, 0.1), Vec3(0.8, 0.9, 0.1)};
    loose.faces = {{0, 1, 2}};
    MeshData floor = test::grid(2, 2), wall = test::grid(2, 2);
    for (Vec3& p : floor.positions) p = Vec3(p.x(), 0, p.y());
    for (Vec3& p : wall.positions) p = Vec3(0, p.x(), p.y());
    const MeshData cloth = test::concat(strip, loose);
    cloth_vertices = cloth.positions.size();
    data = test::concat(cloth, test::concat(floor, wall));
    mesh = std::make_unique<TriMesh>(Index(data.positions.size()), data.faces);
    Body c, o;
    c.name = "cloth";
    c.vertex_end = Index(cloth_vertices);
    c.face_end = Index(cloth.faces.size());
    o.name = "corner";
    o.kind = BodyKind::obstacle;
    o.self_collision = false;
    o.vertex_begin = c.vertex_end, o.vertex_end = Index(data.positions.size());
    o.face_begin = c.face_end, o.face_end = Index(data.faces.size());
    setup.mesh = mesh.get();
    setup.bodies = {c, o};
    setup.rest = data.positions;
    setup.inv_mass.assign(data.positions.size(), 0.0);
    std::fill_n(setup.inv_mass.begin(), cloth_vertices, 1.0);
    state.x = state.p = data.positions;
    state.v.assign(data.positions.size(), Vec3::Zero());
    // The floor rises and the wall advances by `push`; the loose triangle drifts.
    const std::size_t floor_end = cloth_vertices + floor.positions.size();
    for (std::size_t i = cloth_vertices; i < data.positions.size(); ++i) {
      const Vec3 d = i < floor_end ? Vec3(0, push, 0) : Vec3(push, 0, 0);
      state.p[i] = state.x[i] + d, state.v[i] = d / dt;
    }
    for (std::size_t i = 4; i < 7; ++i) state.v[i] = Vec3(0.3, 0, 0), state.p[i] = state.x[i] + dt * state.v[i];
  }
  CcdPipeline crossing() const { return {*mesh, setup.bodies, contact_strategies(18, "sequential", 1, 0.0)}; }
};

TEST(InelasticProjection, ClothPressedByTwoMotionsAtOnceEndsFreeOfContacts) {
  Corner s;
  CcdPipeline crossing = s.crossing();
  ASSERT_GT(crossing.step(s.state.x, s.state.p).contacts.size(), 0u) << "floor and wall cross the strip before";

  {  // What the rigid zones alone make of it: the bottom edge touches floor and wall, two motions — pinched.
    Corner z;
    ImpactZones zones;
    zones.resolve(crossing, z.setup, z.state, Corner::dt, 64);
    EXPECT_GT(zones.pinched_zones, 0u);
  }

  const Positions loose_before(s.state.v.begin() + 4, s.state.v.begin() + 7);
  const Positions scripted_p(s.state.p.begin() + std::ptrdiff_t(s.cloth_vertices), s.state.p.end());
  InelasticProjection projection;
  const InelasticProjection::Outcome out = projection.resolve(crossing, s.setup, s.state, Corner::dt, Corner::gap, 8);
  EXPECT_TRUE(out.left.empty());
  EXPECT_TRUE(crossing.step(s.state.x, s.state.p).contacts.empty());
  EXPECT_EQ(projection.unconverged, 0u);
  EXPECT_EQ(projection.resolved, 1u);
  EXPECT_GT(projection.rows, 0u);
  // The bottom edge ends off the risen floor and the advanced wall, at least `gap` from both.
  for (std::size_t i : {0, 2}) {
    EXPECT_GE(s.state.p[i].x(), Corner::push + Corner::gap * 0.999) << i;
    EXPECT_GE(s.state.p[i].y(), Corner::push + Corner::gap * 0.999) << i;
  }
  // Velocities and positions stay consistent; the scripted vertices and the loose triangle are untouched.
  for (std::size_t i = 0; i < s.cloth_vertices; ++i)
    EXPECT_LT((s.state.p[i] - s.state.x[i] - Corner::dt * s.state.v[i]).norm(), 1e-15) << i;
  EXPECT_EQ(Positions(s.state.v.begin() + 4, s.state.v.begin() + 7), loose_before);
  EXPECT_EQ(Positions(s.state.p.begin() + std::ptrdiff_t(s.cloth_vertices), s.state.p.end()), scripted_p);
}

TEST(InelasticProjection, AContactRowAsksForTheGapAlongTheNormal) {
  Corner s;
  // Vertex 0 (0.01 above the floor at rest) against a floor face rising by 0.02.
  CcdPipeline crossing = s.crossing();
  const StepResult r = crossing.step(s.state.x, s.state.p);
  const auto vf = std::find_if(r.contacts.begin(), r.contacts.end(), [](const Contact& c) {
    // Floor faces are 3–10 (after the strip's 2 and the loose triangle).
    return c.kind == ContactKind::vf && c.vertices[0] == 0 && c.feature_b >= 3 && c.feature_b < 11;
  });
  ASSERT_NE(vf, r.contacts.end());
  const ContactRow row = contact_row(*vf, s.setup, s.state, Corner::dt, Corner::gap);
  EXPECT_NEAR(std::abs(row.n.y()), 1.0, 1e-12);
  EXPECT_NEAR(row.mass, 1.0, 1e-12) << "only the vertex is free, weight 1";
  // Separation 0.01 at t; the face rises 0.02: the vertex must rise 0.01 + gap over the step.
  EXPECT_NEAR(row.normal_velocity(s.state.v), -Corner::push / Corner::dt, 1e-9);
  EXPECT_NEAR(row.target, (Corner::gap - 0.01) / Corner::dt, 1e-9);
}

TEST(ImpactZones, TheLastEscalationTakesInEveryVertexOfATouchedClothBody) {
  Corner s;
  ImpactZones zones;
  zones.reset(s.state.x.size());
  Contact c{};
  c.kind = ContactKind::vf;
  c.vertices = {0, Index(s.cloth_vertices), Index(s.cloth_vertices + 1), Index(s.cloth_vertices + 3)};
  zones.merge({c});
  EXPECT_EQ(zones.merge_bodies(s.setup, {c}), s.cloth_vertices - 1) << "every other cloth vertex joins";
  for (Index v = 0; v < Index(s.cloth_vertices); ++v) EXPECT_EQ(zones.zone(v), zones.zone(0)) << v;
  EXPECT_NE(zones.zone(Index(s.cloth_vertices + 2)), zones.zone(0)) << "obstacle vertices join only by contact";
  EXPECT_EQ(zones.merge_bodies(s.setup, {c}), 0u);
}

}  // namespace
}  // namespace ccdlab
