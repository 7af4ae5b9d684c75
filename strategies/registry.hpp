#pragma once
// The built-in strategies, registered by name: the one place that lists them all (`ccdlab list`).
#include "framework/config/experiment.hpp"
#include "framework/sim/sim_scene.hpp"

namespace ccdlab {

const BuilderRegistry& builder_registry();
const SchedulerRegistry& scheduler_registry();
const TesterRegistry& tester_registry();
const SceneRegistry& scene_registry();
/// The scene simulator's effects (framework/sim/effect.hpp; one file each in strategies/effects/).
const EffectRegistry& effect_registry();
/// The CCD pipeline strategies the scene simulator uses (for contact response and the quality report): the
/// median builder, `scheduler`, the `float` tester inflated by `thickness`, on `threads` threads.
PipelineStrategies contact_strategies(int k, const std::string& scheduler, int threads, double thickness);
/// A simulator for a loaded scene over `mesh` (its topology): the scene's effects made from the registry.
Simulator make_simulator(const SimScene& scene, const TriMesh& mesh);
/// All four, for load_experiment / make_scene / make_strategies.
Registries builtin_registries();

}  // namespace ccdlab
