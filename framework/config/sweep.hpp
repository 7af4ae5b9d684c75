#pragma once
// Sweeps in YAML: an experiment file with a `sweep:` block runs once per combination of values.
//
//   sweep:
//     bv.k: [6, 14, 18, 26]        # any dotted config key: a list of values (or one value); Cartesian product,
//     scheduler: [sequential, phc] #   keys in file order, the last one varying fastest
//     zip:                         # optional: lists of one length, varied together (one axis of the product)
//       scene.resolution: [20, 40]
//       scene.frames: [10, 5]
//     repeats: 3                   # optional (default 1): each combination this many times
//
// Order of runs: repeat 0 goes through the combinations forwards, repeat 1 backwards, … (alternating, so a
// drift of the machine does not favour the first combinations). Each run is the base config plus the run's
// values as `--set` overrides, validated when planned, and gets its own folder under the base output.dir:
//   <output.dir>/<varied values>-<16 hex of the resolved config's hash>/rep<r>/
// A run is complete when its folder holds run.json (written last), so an interrupted sweep resumes. Shard
// i of n (0 ≤ i < n) holds the runs whose index ≡ i (mod n): deterministic, the same on every machine.
#include <cstdint>
#include <string>
#include <vector>

#include "framework/config/experiment.hpp"

namespace ccdlab {

struct SweepRun {
  std::size_t index = 0;               ///< position in the sweep's order (shards split on it)
  int repeat = 0;
  std::size_t combination = 0;         ///< which combination of values (same for every repeat)
  std::vector<std::string> overrides;  ///< "key=value" (the command line's --set first, then the run's values)
  std::string label;                   ///< the varied values, e.g. "bv.k=6,scheduler=phc"
  std::string config_hash;             ///< 16 hex digits of the resolved config without output.dir
  std::string dir;                     ///< where its results go
  ExperimentConfig config;             ///< resolved, output.dir = dir
};

struct SweepPlan {
  std::string source;
  std::string output_dir;              ///< the base output.dir: run folders and the merged runs.csv
  std::vector<std::string> keys;       ///< the varied keys, in file order (zip keys where the zip block is)
  std::size_t combinations = 0;
  int repeats = 1;
  std::vector<SweepRun> runs;          ///< every run in order (repeats × combinations)
};

/// Reads the sweep file and plans every run (each one's config is loaded and validated, so a bad value is
/// reported before anything runs). `overrides` (--set) apply to every run, before the run's own values.
SweepPlan plan_sweep(const std::string& path, const std::vector<std::string>& overrides, const Registries& registries);

/// Whether run index `index` belongs to shard `shard` of `shards`.
[[nodiscard]] inline bool in_shard(std::size_t index, std::size_t shard, std::size_t shards) {
  return index % shards == shard;
}
/// "i/n" → {i, n}, 0 ≤ i < n; throws Error naming the option otherwise.
std::pair<std::size_t, std::size_t> parse_shard(const std::string& text);

/// The file that marks a run folder complete.
inline constexpr const char* kRunDoneFile = "run.json";

}  // namespace ccdlab
