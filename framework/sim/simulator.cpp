#include "framework/sim/simulator.hpp"

#include <chrono>

#include "framework/util/error.hpp"

namespace ccdlab {

Simulator::Simulator(SimSetup setup, std::vector<std::unique_ptr<Effect>> effects, SimOptions options)
    : setup_(std::move(setup)), effects_(std::move(effects)), options_(options), counters_(effects_.size()) {
  if (options_.substeps < 1 || options_.iterations < 1 || !(options_.frame_time > 0))
    fail("simulator: expected substeps >= 1, iterations >= 1 and a positive frame time");
  if (setup_.inv_mass.size() != setup_.rest.size()) fail("simulator: {} masses for {} vertices", setup_.inv_mass.size(), setup_.rest.size());
  for (auto& e : effects_) e->setup(setup_);
  state_.x = setup_.rest;
  state_.p = setup_.rest;
  state_.v.assign(setup_.rest.size(), Vec3::Zero());
  for (std::size_t o = 0; o < setup_.obstacles.size(); ++o) {
    const SimObstacle& ob = setup_.obstacles[o];
    if (!ob.motion.moves()) continue;
    const Body& body = setup_.bodies[std::size_t(ob.body)];
    for (Index v = body.vertex_begin; v < body.vertex_end; ++v) {
      kinematic_.push_back(v);
      kinematic_obstacle_.push_back(int(o));
    }
  }
}

void Simulator::run_stage(Effect::Stage stage, double dt) {
  using Clock = std::chrono::steady_clock;
  for (std::size_t e = 0; e < effects_.size(); ++e) {
    if (effects_[e]->stage() != stage) continue;
    const auto t0 = Clock::now();
    counters_[e].work += effects_[e]->apply(setup_, state_, dt);
    counters_[e].ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    ++counters_[e].calls;
  }
}

void Simulator::substep(double dt) {
  SimState& s = state_;
  run_stage(Effect::Stage::force, dt);
  const std::size_t n = s.x.size();
  for (std::size_t i = 0; i < n; ++i) s.p[i] = setup_.inv_mass[i] > 0 ? Vec3(s.x[i] + dt * s.v[i]) : s.x[i];
  // Scripted obstacles: exactly where their motion puts them at t + dt.
  const double t1 = s.time + dt;
  std::vector<Eigen::Isometry3d> pose(setup_.obstacles.size());
  for (std::size_t o = 0; o < setup_.obstacles.size(); ++o) pose[o] = setup_.obstacles[o].motion.at(t1);
  for (std::size_t k = 0; k < kinematic_.size(); ++k) {
    const auto v = std::size_t(kinematic_[k]);
    s.p[v] = pose[std::size_t(kinematic_obstacle_[k])] * setup_.rest[v];
  }
  for (s.iteration = 0; s.iteration < options_.iterations; ++s.iteration) run_stage(Effect::Stage::constraint, dt);
  for (std::size_t i = 0; i < n; ++i) s.v[i] = (s.p[i] - s.x[i]) / dt;
  run_stage(Effect::Stage::collision, dt);
  s.x = s.p;
  s.time = t1;
}

void Simulator::advance_frame() {
  const double dt = options_.frame_time / options_.substeps;
  for (int i = 0; i < options_.substeps; ++i) substep(dt);
}

double Simulator::kinetic_energy() const {
  double e = 0;
  for (std::size_t i = 0; i < state_.v.size(); ++i)
    if (setup_.inv_mass[i] > 0) e += 0.5 / setup_.inv_mass[i] * state_.v[i].squaredNorm();
  return e;
}

}  // namespace ccdlab
