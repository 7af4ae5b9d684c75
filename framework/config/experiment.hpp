#pragma once
// The experiment config: YAML → typed structs, in this one place. Every key is validated; an unknown key or
// a bad value is an Error "file:line: key: expected …, got …". Top-level keys:
//   name, scene, bv {k}, hierarchy, restructure {threshold}, normal_cones, scheduler, threads, tester,
//   narrow {mode, representative}, memory_limit,
//   output {dir, csv, jsonl, contacts}
// Strategies (hierarchy, scheduler, tester, built-in scenes) are a name or a map {name: …, param: …},
// validated against the registries (see docs/config.md).
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "framework/config/registry.hpp"
#include "framework/config/yaml_reader.hpp"
#include "framework/hierarchy/bvh.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/scene/mesh_sequence.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

using BuilderRegistry = Registry<std::unique_ptr<HierarchyBuilder>>;
using SchedulerRegistry = Registry<std::unique_ptr<TraversalScheduler>>;
using TesterRegistry = Registry<std::unique_ptr<PrimitiveTester>>;
using SceneRegistry = Registry<MeshSequence>;

/// The registries a config is validated against (strategies/registry.hpp provides the built-in ones).
struct Registries {
  const BuilderRegistry& builders;
  const SchedulerRegistry& schedulers;
  const TesterRegistry& testers;
  const SceneRegistry& scenes;
};

struct SceneConfig {
  bool builtin = true;
  StrategyChoice generator;         ///< builtin: the scene generator and its parameters
  std::vector<std::string> files;   ///< from files: one mesh file per frame
  bool self_collision = true;       ///< from files
  std::vector<BodyFiles> bodies;    ///< from files, several bodies (scene: {bodies: […]}); empty otherwise
};

struct OutputConfig {
  std::string dir = "results/run";  ///< CSV, JSONL and the resolved config go here
  bool csv = true;
  bool jsonl = true;
  bool contacts = false;            ///< also write every contact of every step (contacts.csv)
};

struct ExperimentConfig {
  std::string name = "run";
  std::string source;               ///< the YAML file it came from
  SceneConfig scene;
  int k = 18;
  int width = kDefaultBvhWidth;     ///< bv.width: 2 (binary BVTT) or 4 (framework/hierarchy/wide_bvh.hpp)
  EndBoxMode end_boxes = EndBoxMode::automatic;  ///< bv.end_boxes: also test nodes' boxes at both ends (framework/swept/end_boxes.hpp)
  StrategyChoice hierarchy{"median", {}};
  StrategyChoice scheduler{"sequential", {}};
  int threads = 1;
  int split_threads = 0;             ///< not in YAML: `ccdlab bench`'s recording runs (PipelineStrategies::split_threads)
  StrategyChoice tester{"float", {}};
  double restructure_threshold = 0;  ///< restructure: {threshold: …}; 0 = off
  bool normal_cones = false;         ///< normal_cones: true — continuous normal-cone culling of self tests
  NarrowOptions narrow;              ///< narrow: {mode: scalar | batched, representative: fixed | first_free}
  /// memory_limit: resident memory a step may use ("8GiB", "60%", "none"); above the predicted need the step
  /// streams its candidates (framework/pipeline/memory_budget.hpp). Default: 80% of this machine's memory.
  std::string memory_limit = "80%";
  std::uint64_t memory_limit_bytes = 0;  ///< resolved from memory_limit on this machine (0 = none)
  OutputConfig output;
};

/// Reads and validates a YAML experiment, after applying `overrides` ("a.b=value", as from --set). A file with
/// a `sweep:` block is refused unless `sweep_allowed` (then the block is ignored here: framework/config/sweep.hpp).
ExperimentConfig load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                                 const Registries& registries, bool sweep_allowed = false);

/// The fully resolved config (every default filled in) as JSON: what result files record.
nlohmann::json to_json(const ExperimentConfig& config);
/// bv.end_boxes as YAML reads it back: true, false or "auto".
nlohmann::json end_boxes_json(EndBoxMode mode);
/// JSON → YAML text (for config.yaml beside the results).
std::string to_yaml(const nlohmann::json& j);

MeshSequence make_scene(const ExperimentConfig& config, const Registries& registries);
PipelineStrategies make_strategies(const ExperimentConfig& config, const Registries& registries);
/// The strategy section of a config — bv, hierarchy, restructure, normal_cones, scheduler, threads, tester,
/// narrow, memory_limit — from the map `root` into `c` (the keys present; the others keep their values). The
/// caller checks which keys may appear. Errors are located by `r`.
void read_strategy_section(const YamlReader& r, const YAML::Node& root, const Registries& registries, ExperimentConfig& c);

}  // namespace ccdlab
