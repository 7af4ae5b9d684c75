#pragma once
// The built-in strategies, registered by name: the one place that lists them all (`ccdlab list`).
#include "framework/config/experiment.hpp"

namespace ccdlab {

const BuilderRegistry& builder_registry();
const SchedulerRegistry& scheduler_registry();
const TesterRegistry& tester_registry();
const SceneRegistry& scene_registry();
/// All four, for load_experiment / make_scene / make_strategies.
Registries builtin_registries();

}  // namespace ccdlab
