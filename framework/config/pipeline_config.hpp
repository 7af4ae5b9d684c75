#pragma once
// The pipeline's configuration as a reader fills it in: the plain settings (framework/pipeline/
// pipeline_settings.hpp, where every default is) and the three strategies by name and parameters, checked against
// their registries. The experiment config (YAML, --set), `ccdlab step`, the C++ API, the Python module and the
// simulator's ccd_contact effect all fill in one of these and make the pipeline's strategies from it
// (make_strategies), so each check runs once, with the entry point's own spelling of the field.
#include <cstdint>
#include <string>

#include "framework/config/registry.hpp"
#include "framework/hierarchy/bvh.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/pipeline/pipeline_settings.hpp"
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

struct PipelineConfig : PipelineSettings {
  StrategyChoice hierarchy{kDefaultHierarchy, {}};
  StrategyChoice scheduler{kDefaultScheduler, {}};
  StrategyChoice tester{kDefaultTester, {}};
  /// memory_limit's text ("8GiB", "60%", "none"), resolved into memory_limit_bytes on this machine.
  std::string memory_limit = kDefaultMemoryLimit;
};

/// The strategies of `config`, made from their registries, and its settings, validated (spelled by `name`).
PipelineStrategies make_strategies(const PipelineConfig& config, const BuilderRegistry& builders,
                                   const SchedulerRegistry& schedulers, const TesterRegistry& testers,
                                   const SettingName& name = {});

}  // namespace ccdlab
