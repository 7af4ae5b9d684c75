#pragma once
// A simulated scene from YAML (experiments/scenes/<name>.yaml): the cloth pieces and obstacles it is made of,
// the effects it declares (the only physics that runs), time stepping, and the top-level keys every scene has:
//   name, frames (how many to write), resolution (1 = full size: cloth cells scale with √resolution, so
//   triangles scale with resolution), threads, seed
//   frame_time, substeps, iterations, thickness
//   cloth:     [{name, shape: sheet, size: [x, z], cells: [nx, nz], centre: [x, y, z], self_collision}
//              |{name, shape: frustum, centre, r_top, r_bottom, height, segments, rows, self_collision}]
//   obstacles: [{name, shape: sphere | capsule | frustum | mesh, centre | a, b, radius, segments, file,
//               motion: {velocity: [..], move_start, move_end, pivot: [..], axis: [..], spin_rate, spin_start,
//                        keyframes: [{time, offset: [..], angle_deg}]}}]
//   effects:   [{name: gravity, …}, {name: stretch, compliance: …}, …]   (`ccdlab list` shows every effect)
// Errors name the file, line and key, like every config of ccdlab.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "framework/config/registry.hpp"
#include "framework/mesh/mesh_io.hpp"
#include "framework/sim/simulator.hpp"

namespace ccdlab {

using EffectRegistry = Registry<std::unique_ptr<Effect>>;

struct SimScene {
  std::string name, source;
  int frames = 2;
  double resolution = 1;
  MeshData mesh;                  ///< every body concatenated
  SimSetup setup;                 ///< bodies, rest, masses, obstacles, thickness, threads, seed (mesh set by the user)
  std::vector<StrategyChoice> effects;
  SimOptions options;
  nlohmann::json resolved;        ///< every key with its value, defaults filled in (hashed for the cache)
};

/// Reads and checks a scene file; `overrides` are --set key=value (dotted keys: frames=8, resolution=0.1 …).
SimScene load_sim_scene(const std::string& path, const std::vector<std::string>& overrides, const EffectRegistry& effects);

/// A 64-bit content hash of the resolved scene (hex): the cache key of its frames.
std::string scene_hash(const SimScene& scene);

}  // namespace ccdlab
