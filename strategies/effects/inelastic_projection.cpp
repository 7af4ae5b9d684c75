#include "strategies/effects/inelastic_projection.hpp"

#include <algorithm>
#include <cmath>

#include "framework/pipeline/ccd_pipeline.hpp"

namespace ccdlab {

double ContactRow::normal_velocity(const Positions& v) const {
  double vn = 0;
  for (std::size_t k = 0; k < 4; ++k) vn += w[k] * v[vertices[k]].dot(n);
  return vn;
}

void ContactRow::apply(const SimSetup& setup, Positions& v, double j) const {
  for (std::size_t k = 0; k < 4; ++k) v[vertices[k]] += j * w[k] * setup.inv_mass[vertices[k]] * n;
}

ContactRow contact_row(const Contact& c, const SimSetup& setup, const SimState& s, double dt, double gap) {
  ContactRow row;
  const auto [u, t] = c.coords;
  if (c.kind == ContactKind::vf) row.w = {1, -(1 - u - t), -u, -t};
  else row.w = {1 - u, u, -(1 - t), -t};
  for (std::size_t k = 0; k < 4; ++k) row.vertices[k] = std::size_t(c.vertices[k]);
  row.n = contact_normal(c, s.x, s.p);
  if (row.n.squaredNorm() == 0) return row;
  double d0 = 0;  // separation along n at t
  for (std::size_t k = 0; k < 4; ++k) {
    d0 += row.w[k] * s.x[row.vertices[k]].dot(row.n);
    row.mass += row.w[k] * row.w[k] * setup.inv_mass[row.vertices[k]];
  }
  if (d0 < 0) row.n = -row.n, d0 = -d0;
  row.target = (gap - d0) / dt;
  return row;
}

void InelasticProjection::solve(const SimSetup& setup, SimState& s, double tolerance) {
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    ++sweeps;
    double largest = 0;  // the largest change of a row's normal velocity in this sweep
    for (ContactRow& row : rows_) {
      if (row.mass == 0) continue;
      const double dj = std::max(-row.lambda, (row.target - row.normal_velocity(s.v)) / row.mass);
      if (dj == 0) continue;
      row.lambda += dj;
      row.apply(setup, s.v, dj);
      largest = std::max(largest, std::abs(dj) * row.mass);
    }
    if (largest <= tolerance) return;
  }
  ++unconverged;
}

InelasticProjection::Outcome InelasticProjection::resolve(CcdPipeline& crossing, const SimSetup& setup, SimState& s,
                                                          double dt, double gap, int max_rounds) {
  rows_.clear();
  Outcome out;
  // Converged when no row's normal velocity changes by more than a thousandth of the gap over the sub-step.
  const double tolerance = 1e-3 * std::max(gap, 1e-12) / dt;
  for (int round = 0;; ++round) {
    StepResult r = crossing.step(s.x, s.p);
    ++out.detections;
    if (r.contacts.empty()) {
      resolved += round > 0;
      return out;
    }
    if (round == max_rounds) {
      out.left = std::move(r.contacts);
      return out;
    }
    // A contact found again gets a second row: the motion changed, so its time, features' weights and normal
    // did too, and the new row is violated (the features touch at the new time of contact, so their relative
    // normal velocity is −d0 / (toi·dt) < b): every round adds a violated row, none is wasted.
    for (const Contact& c : r.contacts) rows_.push_back(contact_row(c, setup, s, dt, gap));  // sorted: deterministic
    rows += r.contacts.size();
    ++solves;
    solve(setup, s, tolerance);
    for (std::size_t i = 0; i < s.p.size(); ++i)
      if (setup.inv_mass[i] > 0) s.p[i] = s.x[i] + dt * s.v[i];
  }
}

}  // namespace ccdlab
