#pragma once
// The scene simulator: advances a cloth scene frame by frame with exactly the effects the scene lists
// (framework/sim/effect.hpp gives the stages of a sub-step). Position-based dynamics with XPBD constraints
// (Macklin, Müller & Chentanez 2016): unconditionally stable, and a constraint's stiffness (its compliance) does
// not change with the sub-step or the iteration count, so `resolution` and `substeps` can be changed without
// retuning the cloth. Obstacles follow their scripted motion exactly.
//
// Deterministic: effects run one after another in the listed order, and the only parallel work (ccdlab's CCD
// inside `ccd_contact`) returns sorted contacts — the frames are bit-identical whatever the thread count.
#include <memory>
#include <string>
#include <vector>

#include "framework/sim/effect.hpp"

namespace ccdlab {

struct SimOptions {
  double frame_time = 1.0 / 30;  ///< seconds per frame
  int substeps = 4;              ///< sub-steps per frame
  int iterations = 8;            ///< constraint iterations per sub-step
};

class Simulator {
 public:
  Simulator(SimSetup setup, std::vector<std::unique_ptr<Effect>> effects, SimOptions options);

  /// Advances one frame (`substeps` sub-steps).
  void advance_frame();

  [[nodiscard]] const Positions& positions() const { return state_.x; }
  [[nodiscard]] const Positions& velocities() const { return state_.v; }
  [[nodiscard]] double time() const { return state_.time; }
  [[nodiscard]] const SimSetup& setup() const { return setup_; }
  [[nodiscard]] const std::vector<std::unique_ptr<Effect>>& effects() const { return effects_; }
  /// Per effect (same order as effects()): calls, work, milliseconds, since the start.
  [[nodiscard]] const std::vector<EffectCounters>& counters() const { return counters_; }
  /// Σ ½ m |v|² over the cloth (unit mass per vertex where inv_mass > 0).
  [[nodiscard]] double kinetic_energy() const;

 private:
  void substep(double dt);
  void run_stage(Effect::Stage stage, double dt);

  SimSetup setup_;
  std::vector<std::unique_ptr<Effect>> effects_;
  SimOptions options_;
  SimState state_;
  std::vector<EffectCounters> counters_;
  std::vector<Index> kinematic_;      ///< vertices of moving obstacles
  std::vector<int> kinematic_obstacle_;
};

}  // namespace ccdlab
