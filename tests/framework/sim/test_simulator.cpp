// The scene simulator: bit-identical frames whatever the thread count; an effect a scene does not list is never
// evaluated (no wind object, no self pass when self-contact is off); the CCD-based contact response keeps a
// sheet draped over a spinning ball free of crossings; XPBD stretch holds a hanging sheet; located errors in
// scene files; capsule chains and hashed motions; the discrete triangle–triangle test of the quality report.
#include <gtest/gtest.h>

#include <fstream>

#include "framework/sim/quality.hpp"
#include "framework/sim/sim_scene.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

const char* kBallScene = R"(name: small_ball
frames: 12
resolution: 1
threads: 1
seed: 3
frame_time: 0.04
substeps: 2
iterations: 4
thickness: 0.01
cloth:
  - {name: sheet, shape: sheet, size: [1.2, 1.2], cells: [14, 14], centre: [0, 0.42, 0], self_collision: true}
obstacles:
  - {name: ball, shape: sphere, centre: [0, 0, 0], radius: 0.35, segments: 10,
     motion: {spin_rate: 6.0, spin_start: 0.1}}
effects:
  - {name: gravity}
  - {name: damping, rate: 0.2}
  - {name: stretch, compliance: 1.0e-7}
  - {name: bend, compliance: 1.0e-4}
  - {name: obstacle_contact, friction: 0.8}
  - {name: ccd_contact, iterations: 3}
)";

std::string write_scene(const std::string& name, const std::string& text) {
  const auto path = test::temp_dir("sim") / name;
  std::ofstream(path) << text;
  return path.string();
}

struct SimRun {
  std::vector<Positions> frames;
  std::vector<std::string> effects;
  std::vector<EffectCounters> counters;
  std::vector<nlohmann::json> stats;
  std::vector<FrameQuality> quality;
};

SimRun simulate(const std::string& path, const std::vector<std::string>& overrides, bool measure = false) {
  const SimScene scene = load_sim_scene(path, overrides, effect_registry());
  const TriMesh mesh(Index(scene.mesh.positions.size()), scene.mesh.faces);
  Simulator sim = make_simulator(scene, mesh);
  std::unique_ptr<QualityMeter> meter;
  if (measure)
    meter = std::make_unique<QualityMeter>(mesh, scene.setup.bodies,
                                           contact_strategies(18, "sequential", 1, scene.setup.thickness), scene.setup.thickness);
  SimRun r;
  for (int f = 0; f < scene.frames; ++f) {
    if (f > 0) sim.advance_frame();
    r.frames.push_back(sim.positions());
    if (meter) r.quality.push_back(meter->measure(sim.positions()));
  }
  for (const auto& e : sim.effects()) r.effects.emplace_back(e->name()), r.stats.push_back(e->stats());
  r.counters = sim.counters();
  return r;
}

TEST(Simulator, FramesAreBitIdenticalWhateverTheThreadCount) {
  const std::string path = write_scene("ball.yaml", kBallScene);
  const SimRun one = simulate(path, {"threads=1"});
  const SimRun three = simulate(path, {"threads=3"});
  ASSERT_EQ(one.frames.size(), three.frames.size());
  for (std::size_t f = 0; f < one.frames.size(); ++f)
    for (std::size_t v = 0; v < one.frames[f].size(); ++v)
      ASSERT_EQ(one.frames[f][v], three.frames[f][v]) << "frame " << f << " vertex " << v;
  EXPECT_NE(one.frames.back()[0], one.frames.front()[0]) << "the cloth moved";
}

TEST(Simulator, ContactResponseKeepsTheDrapedSheetFreeOfCrossings) {
  const SimRun r = simulate(write_scene("ball.yaml", kBallScene), {}, true);
  for (std::size_t f = 0; f < r.quality.size(); ++f) EXPECT_EQ(r.quality[f].intersecting_pairs, 0u) << "frame " << f;
  // The sheet reached the ball and lies on it: its lowest cloth vertex is below the ball's top.
  double lowest = 1e9;
  for (Index v = 0; v < 15 * 15; ++v) lowest = std::min(lowest, r.frames.back()[std::size_t(v)].y());
  EXPECT_LT(lowest, 0.35);
  const auto ccd = std::find(r.effects.begin(), r.effects.end(), "ccd_contact") - r.effects.begin();
  EXPECT_GT(r.counters[std::size_t(ccd)].work, 0u) << "contacts were resolved";
  EXPECT_GT(r.stats[std::size_t(ccd)]["self_passes"].get<std::uint64_t>(), 0u);
}

TEST(Simulator, AnEffectNotListedIsNeverEvaluated) {
  std::string no_self = kBallScene;
  no_self.replace(no_self.find("{name: ccd_contact, iterations: 3}"), 34, "{name: ccd_contact, iterations: 3, self: false}");
  const SimRun r = simulate(write_scene("noself.yaml", no_self), {"frames=4"});
  const auto ccd = std::size_t(std::find(r.effects.begin(), r.effects.end(), "ccd_contact") - r.effects.begin());
  EXPECT_EQ(r.stats[ccd]["self_passes"].get<std::uint64_t>(), 0u) << "self-contact off: no self pass ever runs";
  EXPECT_GT(r.stats[ccd]["obstacle_passes"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(std::count(r.effects.begin(), r.effects.end(), "wind"), 0) << "no wind listed, no wind evaluated";

  std::string windy = kBallScene;
  windy.replace(windy.find("  - {name: gravity}"), 19, "  - {name: gravity}\n  - {name: wind, vx: 2.0}");
  const SimRun w = simulate(write_scene("wind.yaml", windy), {"frames=3"});
  const auto wind = std::size_t(std::find(w.effects.begin(), w.effects.end(), "wind") - w.effects.begin());
  ASSERT_LT(wind, w.effects.size());
  EXPECT_EQ(w.counters[wind].calls, 2u * 2u) << "once per sub-step: 2 frames advanced × 2 sub-steps";
  EXPECT_EQ(w.counters[wind].work, 2u * 2u * 2u * 14u * 14u) << "every cloth triangle each time";
}

TEST(Simulator, StretchHoldsAPinnedSheetUnderGravity) {
  const std::string hanging = R"(frames: 30
resolution: 1
threads: 1
frame_time: 0.0333
substeps: 4
iterations: 10
cloth:
  - {shape: sheet, size: [1, 1], cells: [10, 10], centre: [0, 1, 0]}
effects:
  - {name: gravity}
  - {name: pin, max_x: -0.49}
  - {name: stretch, compliance: 0}
)";
  const std::string path = write_scene("hanging.yaml", hanging);
  const SimScene scene = load_sim_scene(path, {}, effect_registry());
  const SimRun r = simulate(path, {});
  const TriMesh mesh(Index(scene.mesh.positions.size()), scene.mesh.faces);
  double worst = 0;
  for (Index e = 0; e < mesh.num_edges(); ++e) {
    const auto& ed = mesh.edge(e);
    const double rest = (scene.mesh.positions[std::size_t(ed[0])] - scene.mesh.positions[std::size_t(ed[1])]).norm();
    const double now = (r.frames.back()[std::size_t(ed[0])] - r.frames.back()[std::size_t(ed[1])]).norm();
    worst = std::max(worst, now / rest);
  }
  EXPECT_LT(worst, 1.05) << "inextensible edges stretch by less than 5%";
  EXPECT_EQ(r.frames.back()[0], scene.mesh.positions[0]) << "a pinned corner stays";
  double lowest = 1;
  for (const Positions& x : r.frames) lowest = std::min(lowest, x[10].y());
  EXPECT_LT(lowest, 0.2) << "the free corner swung down (a 1 m pendulum released horizontally)";
}

TEST(SimScene, ErrorsNameTheFileLineAndKey) {
  auto error_of = [](const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
      load_sim_scene(write_scene("bad.yaml", text), overrides, effect_registry());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string base = "frames: 3\nresolution: 1\nthreads: 1\ncloth:\n  - {shape: sheet, size: [1, 1], cells: [2, 2]}\neffects:\n  - {name: gravity}\n";
  EXPECT_NE(error_of(base + "colour: red\n").find("bad.yaml:8: colour: unknown key"), std::string::npos) << error_of(base + "colour: red\n");
  EXPECT_NE(error_of(base, {"effects=[{name: wnd}]"}).find("one of gravity"), std::string::npos);
  EXPECT_NE(error_of("resolution: 1\nthreads: 1\ncloth: []\neffects: []\n").find("frames: required key missing"), std::string::npos);
  EXPECT_NE(error_of(base, {"resolution=0"}).find("resolution"), std::string::npos);
  EXPECT_NE(error_of(base + "obstacles:\n  - {shape: cube}\n").find("obstacles[0].shape: expected one of sphere"), std::string::npos);
  // An effect whose parameters select nothing is refused when the simulator sets it up.
  const std::string path = write_scene("pin.yaml", base);
  EXPECT_THROW(simulate(path, {"effects=[{name: pin, min_x: 5}]"}), Error);
  // ccd_contact's k is checked by the pipeline settings' one check when the effect is made, not later.
  try {
    (void)make_simulator(load_sim_scene(path, {"effects=[{name: ccd_contact, k: 7}]"}, effect_registry()),
                         TriMesh(9, {{0, 1, 4}}));
    ADD_FAILURE() << "k = 7 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ccd_contact: k: expected one of 6, 14, 18, 26, got 7"), std::string::npos) << e.what();
  }
}

TEST(SimScene, ACapsuleChainMovesInItsParentsFrameAndMotionsAreHashed) {
  const std::string chain = R"(frames: 2
resolution: 1
threads: 1
cloth:
  - {shape: sheet, size: [1, 1], cells: [2, 2], centre: [0, 2, 0]}
obstacles:
  - {name: thigh, shape: capsule, a: [0, 1, 0], b: [0, 0.5, 0], radius: 0.1,
     motion: {pivot: [0, 1, 0], axis: [1, 0, 0], keyframes: [{time: 0, angle_deg: 0}, {time: 1, angle_deg: -90}]}}
  - {name: shin, shape: capsule, a: [0, 0.5, 0], b: [0, 0, 0], radius: 0.08, parent: thigh,
     motion: {pivot: [0, 0.5, 0], axis: [1, 0, 0], keyframes: [{time: 0, angle_deg: 0}, {time: 1, angle_deg: 90}]}}
effects:
  - {name: gravity}
)";
  const SimScene scene = load_sim_scene(write_scene("chain.yaml", chain), {}, effect_registry());
  const RigidMotion& shin = scene.setup.obstacles[1].motion;
  for (double t : {0.0, 0.3, 1.0}) {
    // The knee (the shin's top) stays at the thigh's end; the shin turns back to hang straight down.
    const Vec3 knee = shin.at(t) * Vec3(0, 0.5, 0), thigh_end = scene.setup.obstacles[0].motion.at(t) * Vec3(0, 0.5, 0);
    EXPECT_LT((knee - thigh_end).norm(), 1e-12) << "t = " << t;
    EXPECT_LT(((shin.at(t) * Vec3(0, 0, 0)) - (knee - Vec3(0, 0.5, 0))).norm(), 1e-12) << "t = " << t;
  }
  EXPECT_LT((shin.at(1) * Vec3(0, 0.5, 0) - Vec3(0, 1, 0.5)).norm(), 1e-12) << "thigh horizontal at t = 1";
  // A changed keyframe is a different scene (the cache must not return the old frames).
  std::string changed = chain;
  changed.replace(changed.find("angle_deg: 90}"), 14, "angle_deg: 80}");
  EXPECT_NE(scene_hash(scene), scene_hash(load_sim_scene(write_scene("chain2.yaml", changed), {}, effect_registry())));
  std::string orphan = chain;
  orphan.replace(orphan.find("parent: thigh"), 13, "parent: hip");
  try {
    load_sim_scene(write_scene("orphan.yaml", orphan), {}, effect_registry());
    ADD_FAILURE() << "an unknown parent is refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("obstacles[1].parent: expected the name of an obstacle listed before"), std::string::npos) << e.what();
  }
}

TEST(Quality, TriangleIntersectionAndDistance) {
  const Vec3 a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  EXPECT_TRUE(triangles_intersect(a0, a1, a2, Vec3(0.2, 0.2, -1), Vec3(0.3, 0.2, 1), Vec3(0.2, 0.3, 1)));   // pierces
  EXPECT_FALSE(triangles_intersect(a0, a1, a2, Vec3(0.2, 0.2, 0.1), Vec3(0.3, 0.2, 1), Vec3(0.2, 0.3, 1)));  // above
  EXPECT_TRUE(triangles_intersect(a0, a1, a2, Vec3(0.1, 0.1, 0), Vec3(2, 0.1, 0), Vec3(0.1, 2, 0)));         // coplanar overlap
  EXPECT_FALSE(triangles_intersect(a0, a1, a2, Vec3(2, 2, 0), Vec3(3, 2, 0), Vec3(2, 3, 0)));                // coplanar apart
  EXPECT_NEAR(triangle_distance(a0, a1, a2, Vec3(0.2, 0.2, 0.1), Vec3(0.3, 0.2, 1), Vec3(0.2, 0.3, 1)), 0.1, 1e-12);
}

}  // namespace
}  // namespace ccdlab
