#pragma once
// One XPBD distance constraint |p_i − p_j| = rest (Macklin, Müller & Chentanez 2016): projected with its
// Lagrange multiplier so that the stiffness (compliance α, m/N) does not depend on the sub-step or the number
// of iterations. Shared by `stretch` (edges) and `bend` (the two vertices opposite an interior edge).
#include <algorithm>
#include <array>
#include <vector>

#include "framework/sim/effect.hpp"

namespace ccdlab {

struct DistanceConstraints {
  std::vector<std::array<Index, 2>> pairs;
  std::vector<double> rest;
  std::vector<double> lambda;

  void add(Index i, Index j, const Positions& x) {
    pairs.push_back({i, j});
    rest.push_back((x[std::size_t(i)] - x[std::size_t(j)]).norm());
    lambda.push_back(0);
  }

  /// One Gauss–Seidel sweep over the constraints in order (deterministic); multipliers reset at iteration 0.
  std::uint64_t project(const SimSetup& setup, SimState& s, double dt, double compliance) {
    if (s.iteration == 0) std::fill(lambda.begin(), lambda.end(), 0.0);
    const double alpha = compliance / (dt * dt);
    std::uint64_t n = 0;
    for (std::size_t c = 0; c < pairs.size(); ++c) {
      const auto i = std::size_t(pairs[c][0]), j = std::size_t(pairs[c][1]);
      const double wi = setup.inv_mass[i], wj = setup.inv_mass[j];
      if (wi + wj == 0) continue;
      const Vec3 d = s.p[i] - s.p[j];
      const double len = d.norm();
      if (len < 1e-12) continue;
      const double dlambda = (-(len - rest[c]) - alpha * lambda[c]) / (wi + wj + alpha);
      lambda[c] += dlambda;
      const Vec3 g = (dlambda / len) * d;
      s.p[i] += wi * g;
      s.p[j] -= wj * g;
      ++n;
    }
    return n;
  }
};

}  // namespace ccdlab
