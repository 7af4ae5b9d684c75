// Sweeps (framework/config/sweep.hpp): the product and zip of values, alternating repeats, deterministic
// shards, folder names and hashes that do not depend on the machine, and located errors.
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "framework/config/sweep.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

class Sweep : public ::testing::Test {
 protected:
  std::filesystem::path dir = test::temp_dir("sweep");
  std::string write(const std::string& text) {
    auto p = (dir / "sweep.yaml").string();
    std::ofstream(p) << text;
    return p;
  }
  std::string error_of(const std::string& text) {
    auto p = write(text);
    try {
      plan_sweep(p, {}, builtin_registries());
    } catch (const Error& e) {
      std::string msg = e.what();
      for (auto pos = msg.find(p); pos != std::string::npos; pos = msg.find(p)) msg.replace(pos, p.size(), "sweep.yaml");
      return msg;
    }
    return "no error";
  }
  static constexpr const char* kBase = "scene: {builtin: drape_fold, resolution: 6, num_frames: 2}\noutput: {dir: out}\n";
};

TEST_F(Sweep, ProductInFileOrderLastKeyFastestRepeatsAlternate) {
  const SweepPlan plan = plan_sweep(write(std::string(kBase) + "sweep:\n  bv.k: [6, 26]\n  scheduler: [sequential, phc, static]\n"
                                                               "  repeats: 2\n"),
                                    {}, builtin_registries());
  EXPECT_EQ(plan.combinations, 6u);
  EXPECT_EQ(plan.keys, (std::vector<std::string>{"bv.k", "scheduler"}));
  ASSERT_EQ(plan.runs.size(), 12u);
  EXPECT_EQ(plan.runs[0].label, "bv.k=6,scheduler=sequential");
  EXPECT_EQ(plan.runs[1].label, "bv.k=6,scheduler=phc");
  EXPECT_EQ(plan.runs[3].label, "bv.k=26,scheduler=sequential");
  EXPECT_EQ(plan.runs[3].config.k, 26);
  EXPECT_EQ(plan.runs[3].config.scheduler.name, "sequential");
  // Repeat 1 runs the combinations backwards.
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(plan.runs[6 + i].combination, 5 - i);
    EXPECT_EQ(plan.runs[6 + i].repeat, 1);
    EXPECT_EQ(plan.runs[6 + i].config_hash, plan.runs[5 - i].config_hash) << "same combination, same config";
  }
  std::set<std::string> dirs, hashes;
  for (const SweepRun& r : plan.runs) {
    dirs.insert(r.dir);
    hashes.insert(r.config_hash);
    EXPECT_EQ(r.config.output.dir, r.dir);
    EXPECT_EQ(r.dir.rfind("out/", 0), 0u) << "runs live under the base output.dir";
  }
  EXPECT_EQ(dirs.size(), 12u) << "every run its own folder";
  EXPECT_EQ(hashes.size(), 6u) << "one config hash per combination";
  EXPECT_NE(plan.runs[0].dir.find("bv.k=6_scheduler=sequential-" + plan.runs[0].config_hash), std::string::npos);
}

TEST_F(Sweep, ZipGroupsVaryTogetherAndCommandLineSetsApplyToEveryRun) {
  const SweepPlan plan = plan_sweep(write(std::string(kBase) + "sweep:\n  zip:\n    scene.resolution: [4, 8]\n"
                                                               "    scene.num_frames: [3, 2]\n  threads: [1, 2]\n"),
                                    {"bv.k=14"}, builtin_registries());
  ASSERT_EQ(plan.runs.size(), 4u);
  EXPECT_EQ(plan.runs[0].label, "scene.resolution=4,scene.num_frames=3,threads=1");
  EXPECT_EQ(plan.runs[3].label, "scene.resolution=8,scene.num_frames=2,threads=2");
  for (const SweepRun& r : plan.runs) EXPECT_EQ(r.config.k, 14);
}

TEST_F(Sweep, HashIgnoresTheMachineAndTheOutputFolder) {
  const std::string text = std::string(kBase) + "sweep:\n  bv.k: [6]\n";
  const SweepPlan a = plan_sweep(write(text), {"memory_limit=50%"}, builtin_registries());
  const SweepPlan b = plan_sweep(write(text), {"memory_limit=50%", "output.dir=elsewhere"}, builtin_registries());
  EXPECT_EQ(a.runs[0].config_hash, b.runs[0].config_hash);
  const SweepPlan c = plan_sweep(write(text), {"memory_limit=40%"}, builtin_registries());
  EXPECT_NE(a.runs[0].config_hash, c.runs[0].config_hash) << "the limit as written is part of the config";
}

TEST_F(Sweep, ShardsPartitionTheRuns) {
  EXPECT_EQ(parse_shard("0/1"), (std::pair<std::size_t, std::size_t>{0, 1}));
  EXPECT_EQ(parse_shard("3/4"), (std::pair<std::size_t, std::size_t>{3, 4}));
  for (const char* bad : {"4/4", "1", "-1/4", "a/4", "1/0", "1/4x", "/4"})
    EXPECT_THROW(parse_shard(bad), Error) << bad;
  for (std::size_t i = 0; i < 23; ++i) {
    int owners = 0;
    for (std::size_t s = 0; s < 5; ++s) owners += in_shard(i, s, 5);
    EXPECT_EQ(owners, 1);
  }
}

TEST_F(Sweep, ErrorsAreLocated) {
  EXPECT_EQ(error_of(kBase), "sweep.yaml: sweep: required key missing (a sweep file lists the values to vary, e.g. sweep: "
                             "{bv.k: [6, 18]})");
  EXPECT_EQ(error_of(std::string(kBase) + "sweep:\n  zip:\n    bv.k: [6, 14]\n    threads: [1]\n"),
            "sweep.yaml:6: sweep.zip.threads: 1 values, but sweep.zip.bv.k has 2 (zipped lists go together: one length)");
  EXPECT_EQ(error_of(std::string(kBase) + "sweep:\n  bv.k: []\n"), "sweep.yaml:4: sweep.bv.k: expected a non-empty list of values");
  EXPECT_EQ(error_of(std::string(kBase) + "sweep:\n  repeats: many\n"),
            "sweep.yaml:4: sweep.repeats: expected an integer from 1 to 1000, got 'many'");
  const std::string bad_value = error_of(std::string(kBase) + "sweep:\n  bv.k: [6, 7]\n");
  EXPECT_NE(bad_value.find("sweep.yaml: sweep: run 1 (bv.k=7): --set bv.k: bv.k: expected one of 6, 14, 18, 26, got '7'"),
            std::string::npos)
      << bad_value;
  const std::string bad_key = error_of(std::string(kBase) + "sweep:\n  bv.kk: [6]\n");
  EXPECT_NE(bad_key.find("unknown key (did you mean 'k'?)"), std::string::npos) << bad_key;
}

TEST_F(Sweep, RunRefusesASweepFile) {
  const std::string p = write(std::string(kBase) + "sweep:\n  bv.k: [6]\n");
  try {
    load_experiment(p, {}, builtin_registries());
    FAIL() << "a sweep file must not run as one experiment";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(":3: sweep: this file describes a sweep of runs; run it with `ccdlab sweep"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ccdlab
