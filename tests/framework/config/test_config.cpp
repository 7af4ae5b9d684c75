#include <gtest/gtest.h>

#include <fstream>

#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

class Config : public ::testing::Test {
 protected:
  std::filesystem::path dir = test::temp_dir("config");
  std::string write(const std::string& text) {
    auto p = (dir / "exp.yaml").string();
    std::ofstream(p) << text;
    return p;
  }
  std::string error_of(const std::string& text, std::vector<std::string> overrides = {}) {
    auto p = write(text);
    try {
      load_experiment(p, overrides, builtin_registries());
    } catch (const Error& e) {
      std::string msg = e.what();
      auto pos = msg.find(p);
      if (pos != std::string::npos) msg.replace(pos, p.size(), "exp.yaml");
      return msg;
    }
    return "no error";
  }
};

TEST_F(Config, DefaultsAndTypedValues) {
  auto c = load_experiment(write("scene: {builtin: drape_fold, resolution: 10}\nbv: {k: 26}\nthreads: 2\n"
                                 "tester: {name: float, thickness: 0.001}\nscheduler: sequential\n"),
                           {}, builtin_registries());
  EXPECT_EQ(c.name, "exp");
  EXPECT_EQ(c.k, 26);
  EXPECT_EQ(c.threads, 2);
  EXPECT_EQ(c.scheduler.name, "sequential");
  EXPECT_EQ(c.hierarchy.name, "median");
  EXPECT_DOUBLE_EQ(c.tester.params.real("thickness"), 0.001);
  EXPECT_EQ(c.scene.generator.params.integer("resolution"), 10);
  EXPECT_EQ(c.scene.generator.params.integer("num_frames"), 24);  // default filled in
  EXPECT_EQ(c.output.dir, "results/exp");
  auto j = to_json(c);
  EXPECT_EQ(j["scene"]["builtin"], "drape_fold");
  EXPECT_EQ(j["bv"]["k"], 26);
  EXPECT_EQ(c.end_boxes, EndBoxMode::automatic);
  EXPECT_EQ(j["bv"]["end_boxes"], "auto");
  EXPECT_NE(to_yaml(j).find("thickness: 0.001"), std::string::npos);
}

TEST_F(Config, UnknownKeysAreLocatedWithAHint) {
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nschedular: sequential\n"),
            "exp.yaml:2: schedular: unknown key (did you mean 'scheduler'?); valid keys are: name, scene, bv, "
            "hierarchy, restructure, normal_cones, scheduler, threads, tester, narrow, memory_limit, candidate_limit, time_limit, replay, output");
  EXPECT_EQ(error_of("scene:\n  builtin: drape_fold\n  resolution: 10\n  sphere_radus: 1\n"),
            "exp.yaml:4: scene.sphere_radus: unknown key (did you mean 'sphere_radius'?); valid keys are: builtin, "
            "resolution, num_frames, fold_deg, crease, crease_radius, wrinkle, sphere_radius, sphere_segments, "
            "sphere_travel, self_collision");
  EXPECT_NE(error_of("scene: {builtin: drape_fold}\ntester: {name: float, thicknes: 1}\n")
                .find("exp.yaml:2: tester.thicknes: unknown key (did you mean 'thickness'?)"),
            std::string::npos);
}

TEST_F(Config, WrongTypesAndValuesAreLocated) {
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nbv:\n  k: 7\n"), "exp.yaml:3: bv.k: expected one of 6, 14, 18, 26, got '7'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nbv: {end_boxes: sometimes}\n"),
            "exp.yaml:2: bv.end_boxes: expected on, off, auto, true or false, got 'sometimes'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nthreads: many\n"), "exp.yaml:2: threads: expected an integer, got 'many'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nthreads: 0\n"),
            "exp.yaml:2: threads: expected an integer from 1 to 1024, got '0'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold, resolution: 2.5}\n"),
            "exp.yaml:1: scene.resolution: expected an integer, got '2.5'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\ntester: {name: float, thickness: -1}\n"),
            "exp.yaml:2: tester.thickness: expected a number in [0, 1e+300], got '-1'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nscheduler: fastest\n"),
            "exp.yaml:2: scheduler: expected one of sequential, phc, front, static, embree, got 'fastest'");
  EXPECT_EQ(error_of("scene: {builtin: cube}\n"), "exp.yaml:1: scene.builtin: expected one of drape_fold, simulated, barrier_newton, got 'cube'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\noutput: {csv: maybe}\n"),
            "exp.yaml:2: output.csv: expected true or false, got 'maybe'");
  EXPECT_EQ(error_of("bv: {k: 6}\n"), "exp.yaml: scene: required key missing (e.g. scene: {builtin: drape_fold})");
  EXPECT_EQ(error_of("scene: [1, 2]\n"), "exp.yaml:1: scene: expected a map, got a list");
  EXPECT_NE(error_of("scene: {builtin: drape_fold\n").find("exp.yaml:2: YAML syntax error"), std::string::npos);
}

TEST_F(Config, CommandLineOverridesAndTheirErrors) {
  auto p = write("scene: {builtin: drape_fold}\nscheduler: sequential\n");
  auto c = load_experiment(p, {"bv.k=6", "scene.resolution=8", "threads=3", "tester.thickness=0.5"}, builtin_registries());
  EXPECT_EQ(c.k, 6);
  EXPECT_EQ(c.threads, 3);
  EXPECT_EQ(c.scene.generator.params.integer("resolution"), 8);
  EXPECT_EQ(c.tester.name, "float");  // a scalar `tester` became {name: float, thickness: 0.5}
  EXPECT_DOUBLE_EQ(c.tester.params.real("thickness"), 0.5);
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\n", {"bv.k=8"}), "--set bv.k: bv.k: expected one of 6, 14, 18, 26, got '8'");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\n", {"bv.kk=8"}),
            "--set bv.kk: bv.kk: unknown key (did you mean 'k'?); valid keys are: k, width, end_boxes");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\n", {"novalue"}), "--set novalue: expected key=value");
}

TEST_F(Config, ReplayRunsOneStepOfTheSceneBackAndForth) {
  auto c = load_experiment(write("scene: {builtin: drape_fold, resolution: 6, num_frames: 8}\nreplay: {step: 5, frames: 4}\n"),
                           {}, builtin_registries());
  EXPECT_EQ(c.replay.step, 5);
  EXPECT_EQ(c.replay.frames, 4);
  EXPECT_EQ(to_json(c)["replay"]["step"], 5);
  const MeshSequence own = make_scene(load_experiment(write("scene: {builtin: drape_fold, resolution: 6, num_frames: 8}\n"),
                                                      {}, builtin_registries()),
                                      builtin_registries());
  const MeshSequence replay = make_scene(c, builtin_registries());
  ASSERT_EQ(replay.num_frames(), 4);
  EXPECT_EQ(replay.topology().num_faces(), own.topology().num_faces());
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(replay.frame_label(i), own.frame_label(5 + i % 2));
    EXPECT_EQ(replay.frame(i), own.frame(5 + i % 2)) << "frame " << i;
  }
  EXPECT_FALSE(to_json(load_experiment(write("scene: {builtin: drape_fold}\n"), {}, builtin_registries())).contains("replay"));
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nreplay: {step: 1, frame: 3}\n"),
            "exp.yaml:2: replay.frame: unknown key (did you mean 'frames'?); valid keys are: step, frames");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nreplay: {frames: 3}\n"),
            "exp.yaml:2: replay.step: required key missing (e.g. replay: {step: 19, frames: 11})");
  EXPECT_EQ(error_of("scene: {builtin: drape_fold}\nreplay: {step: 1, frames: 1}\n"),
            "exp.yaml:2: replay.frames: expected an integer in [2, 1000000], got '1'");
  try {  // a step the scene does not have: found when the scene is made
    (void)make_scene(load_experiment(write("scene: {builtin: drape_fold, resolution: 6, num_frames: 8}\nreplay: {step: 7}\n"),
                                     {}, builtin_registries()),
                     builtin_registries());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("replay.step: expected 0 … 6"), std::string::npos) << e.what();
  }
}

TEST_F(Config, FrameScenesResolvePathsAgainstTheConfigFile) {
  auto c = load_experiment(write("scene: {frames: \"meshes/%03d.ply\", first: 8, last: 10}\n"), {}, builtin_registries());
  ASSERT_FALSE(c.scene.builtin);
  ASSERT_EQ(c.scene.files.size(), 3u);
  EXPECT_EQ(c.scene.files[0], (dir / "meshes/008.ply").lexically_normal().string());
  auto list = load_experiment(write("scene: {frames: [a.obj, b.obj]}\n"), {"scene.frames=[x.ply, y.ply]"}, builtin_registries());
  EXPECT_EQ(list.scene.files, (std::vector<std::string>{"x.ply", "y.ply"}));  // --set: relative to the working dir
  EXPECT_EQ(error_of("scene: {frames: \"f/%03d.ply\", first: 3}\n"),
            "exp.yaml:1: scene: expected keys 'first' and 'last' with a frame pattern, got a map");
  EXPECT_EQ(error_of("scene: {frames: \"f/%03d.ply\", first: 3, last: 3}\n"),
            "exp.yaml:1: scene.last: expected an integer > first (3), got '3'");
  EXPECT_EQ(error_of("scene: {frames: [a.ply]}\n"), "exp.yaml:1: scene.frames: expected at least 2 frames, got a list");
}

}  // namespace
}  // namespace ccdlab
