#pragma once
// The steps a barrier (IPC-style) solver asks CCD, as benchmark input: the implicit cloth of
// <ccdlab/barrier_solver.hpp> — a sheet folded into layers a little more than a contact distance apart (the
// barrier's d̂ is 0.8 of the gap) on a sphere, the layers closing onto each other and sliding along the folds —
// run for a few frames, keeping each Newton iteration's (x, x + Δx) before its line search. The Newton steps carry
// layers through and along their neighbours: the tangled, contact-dense steps of docs/narrow-phase.md ("Steps a
// barrier solver asks for").
//   scene: {builtin: barrier_newton, cells: 204, pleats: 6, solver_frames: 2}
// Recorded once into a folder (PLY frames + meta.json, as simulated scenes are) and reused while the parameters
// and the solver are the same: frames 2i and 2i + 1 are query i's x and x + Δx.
#include <string>

#include "framework/scene/mesh_sequence.hpp"

namespace ccdlab {

struct BarrierNewtonParams {
  int cells = 101;          ///< vertices per side of the sheet (2·(cells − 1)² triangles)
  int pleats = 6;           ///< layers of the accordion fold
  int frames = 2;           ///< frames the solver runs (h = 1/60 s)
  int max_iterations = 6;   ///< Newton iterations per frame at most (each one a recorded query)
  double wrinkle = 0;       ///< each layer's waves, in layer gaps (0: flat layers)
  double drop_speed = 0.6;  ///< the top layer's initial downward speed, m/s (the lowest starts at rest)
  double slide_speed = 1.2; ///< each layer's initial speed along the folds, m/s, alternating in sign
  std::string dir;          ///< folder of the recording (empty: results/scenes/barrier_newton-HASH)
};

/// Runs the solver and records its queries into their folder, unless it holds them already; returns the folder.
std::string record_barrier_newton(const BarrierNewtonParams& params, bool progress = true);

}  // namespace ccdlab
