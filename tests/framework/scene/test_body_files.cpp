// Several bodies from files (scene: {bodies: […]}): a cloth sequence falling on a still obstacle read from one
// file. The bodies are concatenated with their flags, the pipeline finds exactly the brute-force contacts, only
// between the cloth and the obstacle when the cloth's self-collision is off; bad inputs name the body.
#include <gtest/gtest.h>

#include <fstream>

#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "support/error_of.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::error_of;

struct Files {
  std::filesystem::path dir;
  std::vector<std::string> cloth;
  std::string obstacle;
};

/// A 6×6 cloth in three frames passing down through a 4×4 obstacle sheet, written as PLY files.
Files write_scene(const char* name) {
  Files f{test::temp_dir(name), {}, {}};
  const MeshData cloth = test::grid(6, 6);
  MeshData obstacle = test::grid(4, 4);
  for (Vec3& p : obstacle.positions) p = Vec3(1.4 * p.x() - 0.2, 1.4 * p.y() - 0.2, 0.0);
  f.obstacle = (f.dir / "obstacle.ply").string();
  write_ply(f.obstacle, obstacle.positions, obstacle.faces);
  for (int i = 0; i < 3; ++i) {
    Positions x = cloth.positions;
    for (Vec3& p : x) p += Vec3(0, 0, 0.1 - 0.1 * i + 0.01 * std::sin(9 * p.x()));
    f.cloth.push_back((f.dir / fmt::format("cloth_{}.ply", i)).string());
    write_ply(f.cloth.back(), x, cloth.faces);
  }
  return f;
}

PipelineStrategies strategies(const std::string& scheduler, int threads) {
  PipelineStrategies s;
  s.threads = threads;
  s.builder = builder_registry().make({"median", builder_registry().find("median")->defaults()});
  s.scheduler = scheduler_registry().make({scheduler, scheduler_registry().find(scheduler)->defaults()});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  return s;
}

TEST(BodyFiles, ClothOnAStillObstacleMatchesBruteForce) {
  const Files f = write_scene("bodies");
  for (bool cloth_self : {false, true}) {
    const MeshSequence scene = load_body_files({{"cloth", f.cloth, cloth_self, false}, {"floor", {f.obstacle}, true, true}});
    ASSERT_EQ(scene.num_frames(), 3);
    ASSERT_EQ(scene.bodies().size(), 2u);
    const Body& cloth = scene.bodies()[0];
    const Body& floor = scene.bodies()[1];
    EXPECT_EQ(cloth.kind, BodyKind::cloth);
    EXPECT_EQ(cloth.self_collision, cloth_self);
    EXPECT_EQ(floor.kind, BodyKind::obstacle);
    EXPECT_FALSE(floor.self_collision) << "a kinematic body never self-collides";
    EXPECT_EQ(floor.vertex_begin, cloth.vertex_end);
    EXPECT_EQ(scene.frame(2).size(), std::size_t(floor.vertex_end));
    EXPECT_EQ(scene.frame(2)[std::size_t(floor.vertex_begin)], scene.frame(0)[std::size_t(floor.vertex_begin)]);
    for (const auto& [scheduler, threads] : std::vector<std::pair<std::string, int>>{{"sequential", 1}, {"phc", 2}}) {
      CcdPipeline pipeline(scene.topology(), scene.bodies(), strategies(scheduler, threads));
      const CollisionRules rules(scene.topology(), scene.bodies());
      std::size_t total = 0;
      for (int s = 0; s < scene.num_steps(); ++s) {
        const Positions x0 = scene.frame(s), x1 = scene.frame(s + 1);
        StepResult r = pipeline.step(x0, x1);
        auto expected = brute_force_contacts(scene.topology(), rules, x0, x1, *pipeline.strategies().tester);
        std::vector<std::tuple<ContactKind, Index, Index>> got, want;
        for (const Contact& c : r.contacts) got.push_back(c.key());
        for (const Contact& c : expected) want.push_back(c.key());
        std::sort(want.begin(), want.end());
        EXPECT_EQ(got, want) << scheduler << " step " << s;
        for (const Contact& c : r.contacts) {
          const bool a_floor = c.vertices[0] >= floor.vertex_begin;
          const bool b_floor = c.vertices[c.kind == ContactKind::vf ? 1 : 2] >= floor.vertex_begin;
          EXPECT_FALSE(a_floor && b_floor) << "the obstacle is never tested against itself";
          if (!cloth_self) {
            EXPECT_NE(a_floor, b_floor) << "cloth self-collision is off";
          }
        }
        total += r.contacts.size();
      }
      EXPECT_GT(total, 10u) << "the cloth must pass through the obstacle";
    }
  }
}

TEST(BodyFiles, ConfigReadsBodiesAndNamesBadOnes) {
  const Files f = write_scene("bodies_cfg");
  const auto path = (f.dir / "exp.yaml").string();
  const auto load = [&](const std::string& text) {
    std::ofstream(path) << text;
    return load_experiment(path, {}, builtin_registries());
  };
  const auto error = [&](const std::string& text) {
    try {
      (void)make_scene(load(text), builtin_registries());
    } catch (const Error& e) {
      std::string m = e.what();
      for (auto pos = m.find(path); pos != std::string::npos; pos = m.find(path)) m.replace(pos, path.size(), "exp.yaml");
      return m;
    }
    return std::string("no error");
  };
  const ExperimentConfig c = load("scene:\n  bodies:\n"
                                  "    - {name: cloth, frames: \"cloth_%d.ply\", first: 0, last: 2, self_collision: false}\n"
                                  "    - {name: floor, frames: obstacle.ply, kinematic: true}\n");
  ASSERT_EQ(c.scene.bodies.size(), 2u);
  EXPECT_EQ(c.scene.bodies[0].files, f.cloth);
  EXPECT_EQ(c.scene.bodies[1].files, (std::vector<std::string>{f.obstacle}));
  EXPECT_TRUE(c.scene.bodies[1].kinematic);
  const MeshSequence scene = make_scene(c, builtin_registries());
  EXPECT_EQ(scene.num_frames(), 3);
  const auto j = to_json(c);
  EXPECT_EQ(j["scene"]["bodies"][1]["kinematic"], true);
  EXPECT_EQ(j["scene"]["bodies"][0]["self_collision"], false);

  EXPECT_EQ(error("scene:\n  bodies:\n    - {frames: \"cloth_%d.ply\", first: 0, last: 2}\n"
                  "    - {frames: [cloth_0.ply, cloth_1.ply]}\n"),
            "exp.yaml:4: scene.bodies[1].frames: expected 3 frames like the bodies before it (one file per frame), or "
            "one file (a still body), got a list");
  EXPECT_EQ(error("scene:\n  bodies:\n    - {frames: obstacle.ply}\n"),
            "exp.yaml:3: scene.bodies: expected at least one body with 2 or more frames, got a list");
  EXPECT_EQ(error("scene:\n  bodies:\n    - {frames: obstacle.ply, kinematic: true, self_collision: true}\n"
                  "    - {frames: [cloth_0.ply, cloth_1.ply]}\n"),
            "exp.yaml:3: scene.bodies[0].self_collision: expected false or absent for a kinematic body (obstacles never "
            "self-collide), got 'true'");
  EXPECT_NE(error("scene:\n  bodies:\n    - {frames: [cloth_0.ply, cloth_1.ply], kinematik: true}\n").find(
                "scene.bodies[0].kinematik: unknown key (did you mean 'kinematic'?)"),
            std::string::npos);
  EXPECT_EQ(error("scene:\n  frames: [cloth_0.ply, cloth_1.ply]\n  bodies: []\n"),
            "exp.yaml:2: scene: expected one of 'builtin' (a generated scene), 'frames' (mesh files) or 'bodies' (several "
            "bodies), got a map");
  // A body's frame with another vertex count is named with its file, before any step.
  std::vector<std::string> bad = f.cloth;
  bad[2] = f.obstacle;
  EXPECT_NE(error_of([&] { (void)load_body_files({{"cloth", bad, true, false}}); }).find("obstacle.ply: frame 2 has"),
            std::string::npos);
}

}  // namespace
}  // namespace ccdlab
