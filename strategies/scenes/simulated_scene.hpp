#pragma once
// Simulated scenes as CCD input: runs the scene simulator on a scene file (experiments/scenes/<name>.yaml) —
// or finds its frames cached under results/scenes/<name>-<hash>/ — and serves the frames as a MeshSequence
// with the scene's own bodies (cloth with its self-collision flag, obstacles), so an experiment can name a
// scene instead of frame files:  scene: {builtin: simulated, file: experiments/scenes/cloth_ball.yaml,
// num_frames: 8, resolution: 0.1}.
#include <string>
#include <vector>

#include "framework/scene/mesh_sequence.hpp"

namespace ccdlab {

struct SimulateRequest {
  std::string scene;                   ///< scene YAML file
  std::vector<std::string> overrides;  ///< key=value (frames=8, resolution=0.1, threads=2 …)
  std::string out;                     ///< folder; empty = results/scenes/<name>-<scene hash>
  bool force = false;                  ///< simulate even when the folder holds this scene's frames
  bool progress = true;
};

/// Simulates the scene into its folder (PLY frames + meta.json), unless that folder already holds it;
/// returns the folder. `print`: the per-frame table on stdout.
std::string simulate_to_folder(const SimulateRequest& request, bool print);

/// The frames `first_frame` … `last_frame` (0 = the last) of a simulated folder (meta.json + frame_NNNN.ply),
/// with the scene's bodies: a window of a long animation (where the cloth is folded, not still falling);
/// at least two frames.
MeshSequence load_simulated_frames(const std::string& folder, int first_frame = 0, int last_frame = 0);

}  // namespace ccdlab
