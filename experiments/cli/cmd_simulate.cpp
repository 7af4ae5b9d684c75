// `ccdlab simulate SCENE.yaml [--set key=value …] [--out DIR] [--force]`: runs the scene simulator
// (framework/sim/) with exactly the effects the scene lists and writes its frames as PLY (frame_0000.ply …)
// and meta.json: the scene, its resolved parameters and content hash, the revision, and per frame the
// simulation time of every effect, what each did, the intersecting and too-close triangle pairs, the kinetic
// energy. Frames are cached by the scene's hash (strategies/scenes/simulated_scene.hpp).
#include "experiments/cli/commands.hpp"
#include "strategies/scenes/simulated_scene.hpp"

namespace ccdlab::cli {

int simulate_command(const SimulateOptions& o) {
  simulate_to_folder({o.scene, o.overrides, o.out, o.force, o.progress}, true);
  return 0;
}

}  // namespace ccdlab::cli
