#pragma once
// The experiment config: YAML → typed structs, in this one place. Every key is validated; an unknown key or
// a bad value is an Error "file:line: key: expected …, got …". Top-level keys: name, scene, replay {step, frames},
// output {dir, csv, jsonl, contacts}, and the pipeline's settings (framework/config/settings.def).
// Strategies (hierarchy, scheduler, tester, built-in scenes) are a name or a map {name: …, param: …},
// validated against the registries (see docs/config.md).
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "framework/config/pipeline_config.hpp"
#include "framework/config/registry.hpp"
#include "framework/config/yaml_reader.hpp"
#include "framework/hierarchy/bvh.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/scene/mesh_sequence.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {


struct SceneConfig {
  bool builtin = true;
  StrategyChoice generator;         ///< builtin: the scene generator and its parameters
  std::vector<std::string> files;   ///< from files: one mesh file per frame
  bool self_collision = true;       ///< from files
  std::vector<BodyFiles> bodies;    ///< from files, several bodies (scene: {bodies: […]}); empty otherwise
};

/// replay: one step of the scene run again and again (replay_step, mesh_sequence.hpp): a steady state to time.
struct ReplayConfig {
  int step = -1;    ///< the scene's step (frame step → step + 1); -1 = the scene's own steps, in order
  int frames = 11;  ///< frames of the replay: frames − 1 steps
};

struct OutputConfig {
  std::string dir = "results/run";  ///< CSV, JSONL and the resolved config go here
  bool csv = true;
  bool jsonl = true;
  bool contacts = false;            ///< also write every contact of every step (contacts.csv)
};

/// An experiment: its scene and outputs, and the pipeline's configuration (pipeline_config.hpp).
struct ExperimentConfig : PipelineConfig {
  std::string name = "run";
  std::string source;               ///< the YAML file it came from
  SceneConfig scene;
  ReplayConfig replay;
  OutputConfig output;
};

/// Reads and validates a YAML experiment, after applying `overrides` ("a.b=value", as from --set). A file with
/// a `sweep:` block is refused unless `sweep_allowed` (then the block is ignored here: framework/config/sweep.hpp).
ExperimentConfig load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                                 const Registries& registries, bool sweep_allowed = false);

/// The fully resolved config (every default filled in) as JSON: what result files record.
nlohmann::json to_json(const ExperimentConfig& config);
/// JSON → YAML text (for config.yaml beside the results).
std::string to_yaml(const nlohmann::json& j);

MeshSequence make_scene(const ExperimentConfig& config, const Registries& registries);
PipelineStrategies make_strategies(const PipelineConfig& config, const Registries& registries, const SettingName& name = {});

}  // namespace ccdlab
