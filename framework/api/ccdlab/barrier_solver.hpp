#pragma once
// An implicit cloth stepped with a log-barrier contact term (Incremental Potential Contact, Li et al. 2020), the
// kind of solver that asks CCD the questions of docs/proximity.md. Each frame minimises
//     E(x) = Σ m/(2h²)·|x − x̃|²  +  Σ springs k/2·(|xa − xb| − L)²  +  κ·Σ pairs closer than d̂ of b(d),
//     b(d) = −(d − d̂)²·ln(d / d̂),     x̃ = x + h·v + h²·g,
// by Newton's method. Every iteration asks the detector two things (active_set_and_step): the pairs closer than d̂
// now — the barrier's active set, with each pair's distance and closest points — and how far the Newton step may
// go before any pair comes closer than the separation s; the line search starts below that and backtracks on E,
// whose every evaluation asks for the pairs near the trial positions (proximity).
//
// The Hessian: masses, springs with their compressive part dropped (positive semi-definite), and the barrier's
// Gauss–Newton part κ·b''(d)·∇d∇dᵀ (b'' > 0 below d̂). ∇d for a pair with closest points p (weights w of its first
// feature's vertices) and q (weights u of the second's): ∂d/∂x = w·n and −u·n, n = (p − q) / d. A pair whose closest
// points are a vertex and a vertex (or a vertex and an edge) is reported once per face or edge holding them; it
// counts once (the pairs are merged by the vertices that carry weight on each side, as barrier solvers do).
//
// Header-only, installed with the package, on the public API (Detector's proximity and active_set_and_step), so that
// examples/barrier_cloth and the `barrier_newton` scene (strategies/scenes/, which records the solver's CCD queries
// as benchmark steps) run the same code. Needs Eigen (sparse Cholesky).
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <utility>
#include <vector>

namespace ccdlab::barrier {

using Vec3 = Eigen::Vector3d;
using Point = std::array<double, 3>;
using Triangle = std::array<int, 3>;

struct ClothScene {
  std::vector<Point> x;  // cloth vertices, then the sphere's, then the floor's four
  int cloth_vertices = 0;
  std::vector<Triangle> cloth, sphere, floor;  // each in its own body's vertex ids
  std::vector<std::array<int, 2>> springs;
  std::vector<double> rest;
};

/// An n×n sheet of side 1 above a sphere of radius r at the origin (stacks × slices triangles), on a floor (a square
/// of side 3 at z = −r). `pleats` = 1: flat at height z0. `pleats` > 1: folded like an accordion across x into that
/// many layers `gap` apart, the lowest at z0 (the springs keep the flat sheet's rest lengths; a fold is one row of
/// cells standing upright). `wrinkle` > 0: each layer waves by up to that height (wavelength 8 cells, its phase
/// turning from layer to layer), so that neighbouring layers come close in some places and not in others.
inline ClothScene make_sheet_over_sphere(int n, double z0, double r, int stacks, int slices, int pleats = 1, double gap = 0,
                                         double wrinkle = 0) {
  ClothScene s;
  const double h = 1.0 / (n - 1);
  const int per_layer = std::max(1, (n + pleats - 1) / pleats);  // columns per layer
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      Point flat{i * h - 0.5, j * h - 0.5, z0};
      if (pleats > 1) {  // column i lies in layer i / per_layer, running back and forth
        const int layer = i / per_layer, in = i % per_layer;
        const double width = (per_layer - 1) * h;
        flat[0] = (layer % 2 == 0 ? in * h : width - in * h) - width / 2;
        const double pi = std::acos(-1.0), w = 2 * pi / (8 * h);
        flat[2] = z0 + layer * gap + wrinkle * std::sin(w * flat[0] + 1.3 * layer) * std::sin(w * flat[1] + 0.7 * layer);
      }
      s.x.push_back(flat);
      const int v = j * n + i;
      if (i + 1 < n) s.springs.push_back({v, v + 1});
      if (j + 1 < n) s.springs.push_back({v, v + n});
      if (i + 1 < n && j + 1 < n) {
        s.springs.push_back({v, v + n + 1}), s.springs.push_back({v + 1, v + n});  // shear
        s.cloth.push_back({v, v + 1, v + n + 1}), s.cloth.push_back({v, v + n + 1, v + n});
      }
    }
  s.cloth_vertices = n * n;
  for (const auto& [a, b] : s.springs) {  // rest lengths of the flat sheet
    const int ia = a % n, ja = a / n, ib = b % n, jb = b / n;
    s.rest.push_back(h * std::hypot(double(ia - ib), double(ja - jb)));
  }
  // The sphere: two poles and (stacks − 1) rings.
  const double pi = std::acos(-1.0);
  std::vector<Point> ball{{0, 0, r}};
  for (int k = 1; k < stacks; ++k)
    for (int l = 0; l < slices; ++l) {
      const double th = pi * k / stacks, ph = 2 * pi * l / slices;
      ball.push_back({r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  ball.push_back({0, 0, -r});
  const int south = int(ball.size()) - 1;
  const auto ring = [&](int k, int l) { return 1 + (k - 1) * slices + (l % slices); };
  for (int l = 0; l < slices; ++l) {
    s.sphere.push_back({0, ring(1, l), ring(1, l + 1)});
    for (int k = 1; k + 1 < stacks; ++k) {
      s.sphere.push_back({ring(k, l), ring(k + 1, l), ring(k + 1, l + 1)});
      s.sphere.push_back({ring(k, l), ring(k + 1, l + 1), ring(k, l + 1)});
    }
    s.sphere.push_back({south, ring(stacks - 1, l + 1), ring(stacks - 1, l)});
  }
  s.x.insert(s.x.end(), ball.begin(), ball.end());
  for (const Point& p : {Point{-1.5, -1.5, -r}, {1.5, -1.5, -r}, {1.5, 1.5, -r}, {-1.5, 1.5, -r}}) s.x.push_back(p);
  s.floor = {{0, 1, 2}, {0, 2, 3}};
  return s;
}

inline Vec3 at(const std::vector<Point>& x, int v) { return {x[v][0], x[v][1], x[v][2]}; }

/// One barrier pair: the vertices and the weight each carries in ∇d (p's positive, q's negative), and d.
struct BarrierPair {
  std::array<int, 4> v;
  std::array<double, 4> w;
  double d;
  Vec3 n;  // (p − q) / d
};

/// The active set as barrier pairs, each primitive pair once (merged by the vertices that carry weight).
template <class Proximities>
std::vector<BarrierPair> barrier_pairs(const Proximities& near, const std::vector<Point>& x) {
  std::map<std::array<int, 8>, BarrierPair> merged;
  const auto add = [&](const std::array<int, 4>& v, const std::array<double, 4>& w, int first_side) {
    BarrierPair b{v, w, 0, Vec3::Zero()};
    Vec3 p = Vec3::Zero(), q = Vec3::Zero();
    for (int i = 0; i < 4; ++i) (i < first_side ? p : q) += std::abs(w[i]) * at(x, v[i]);
    b.d = (p - q).norm();
    b.n = (p - q) / b.d;
    std::array<int, 8> key;  // the weighted vertices of each side, sorted; the two sides in order
    std::array<int, 4> a{-1, -1, -1, -1}, c{-1, -1, -1, -1};
    for (int i = 0, na = 0, nc = 0; i < 4; ++i)
      if (w[i] != 0) (i < first_side ? a[na++] : c[nc++]) = v[i];
    std::sort(a.begin(), a.end()), std::sort(c.begin(), c.end());
    if (c < a) std::swap(a, c);
    std::copy(a.begin(), a.end(), key.begin()), std::copy(c.begin(), c.end(), key.begin() + 4);
    merged.emplace(key, b);
  };
  for (const auto& p : near.vf) {
    const double w1 = p.coords[0], w2 = p.coords[1];
    add(p.vertices, {1, -(1 - w1 - w2), -w1, -w2}, 1);
  }
  for (const auto& p : near.ee) {
    const double s = p.coords[0], t = p.coords[1];
    add(p.vertices, {1 - s, s, -(1 - t), -t}, 2);
  }
  std::vector<BarrierPair> out;
  for (auto& [key, b] : merged) out.push_back(b);
  return out;
}

template <class Detector>
struct Solver {
  using Proximities = decltype(std::declval<Detector&>().proximity(std::declval<std::vector<Point>&>(), 1.0));
  Solver(ClothScene& s, Detector& d) : scene(s), detector(d) {}
  ClothScene& scene;
  Detector& detector;
  double h = 1.0 / 60, mass = 0, k = 2e3, kappa = 1e2, dhat = 5e-3, separation = 5e-4;
  Vec3 gravity{0, 0, -9.81};
  int max_iterations = 50;
  /// When set, the line search's collision-free step size is this detector's earliest time of contact from x to
  /// x + Δx instead of active_set_and_step's — e.g. a Detector with the `additive` tester at thickness =
  /// separation, as most IPC codes run (examples/barrier_cloth `additive`); the active set still comes from
  /// `detector`. Not conservative in floating point: the end-of-frame separation check is what tells.
  Detector* step_detector = nullptr;
  /// Called with each Newton iteration's x and x + Δx, before the line search: what the solver asks CCD.
  std::function<void(const std::vector<Point>& x, const std::vector<Point>& target)> on_newton_step;
  std::vector<Point> xt;  // x̃

  int dofs() const { return 3 * scene.cloth_vertices; }

  static double barrier(double d, double dhat) { return -(d - dhat) * (d - dhat) * std::log(d / dhat); }
  static double barrier_1(double d, double dhat) { return -2 * (d - dhat) * std::log(d / dhat) - (d - dhat) * (d - dhat) / d; }
  static double barrier_2(double d, double dhat) {
    return -2 * std::log(d / dhat) - 4 * (d - dhat) / d + (d - dhat) * (d - dhat) / (d * d);
  }

  double elastic_energy(const std::vector<Point>& x) const {
    double e = 0;
    for (int i = 0; i < scene.cloth_vertices; ++i) e += mass / (2 * h * h) * (at(x, i) - at(xt, i)).squaredNorm();
    for (std::size_t s = 0; s < scene.springs.size(); ++s) {
      const double l = (at(x, scene.springs[s][0]) - at(x, scene.springs[s][1])).norm() - scene.rest[s];
      e += k / 2 * l * l;
    }
    return e;
  }
  /// E at x, given the pairs near x.
  double energy(const std::vector<Point>& x, const Proximities& near) const {
    double e = elastic_energy(x);
    for (const BarrierPair& b : barrier_pairs(near, x)) e += kappa * barrier(b.d, dhat);
    return e;
  }

  /// Gradient and Hessian (PSD) of E at x with the active set `pairs`; obstacle vertices are fixed (no dofs).
  void derivatives(const std::vector<Point>& x, const std::vector<BarrierPair>& pairs, Eigen::VectorXd& g,
                   Eigen::SparseMatrix<double>& H) const {
    g = Eigen::VectorXd::Zero(dofs());
    std::vector<Eigen::Triplet<double>> t;
    const auto block = [&](int a, int b, const Eigen::Matrix3d& m) {
      if (a >= scene.cloth_vertices || b >= scene.cloth_vertices) return;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * a + r, 3 * b + c, m(r, c));
    };
    for (int i = 0; i < scene.cloth_vertices; ++i) {
      g.segment<3>(3 * i) += mass / (h * h) * (at(x, i) - at(xt, i));
      block(i, i, mass / (h * h) * Eigen::Matrix3d::Identity());
    }
    for (std::size_t s = 0; s < scene.springs.size(); ++s) {
      const auto [a, b] = scene.springs[s];
      const Vec3 d = at(x, a) - at(x, b);
      const double l = d.norm(), L = scene.rest[s];
      const Vec3 u = d / l;
      g.segment<3>(3 * a) += k * (l - L) * u, g.segment<3>(3 * b) -= k * (l - L) * u;
      const Eigen::Matrix3d m = k * (u * u.transpose() + std::max(0.0, 1 - L / l) * (Eigen::Matrix3d::Identity() - u * u.transpose()));
      block(a, a, m), block(b, b, m), block(a, b, -m), block(b, a, -m);
    }
    for (const BarrierPair& p : pairs) {
      const double d1 = kappa * barrier_1(p.d, dhat), d2 = kappa * barrier_2(p.d, dhat);
      for (int i = 0; i < 4; ++i) {
        if (p.w[i] == 0 || p.v[i] >= scene.cloth_vertices) continue;
        g.segment<3>(3 * p.v[i]) += d1 * p.w[i] * p.n;
        for (int j = 0; j < 4; ++j)
          if (p.w[j] != 0) block(p.v[i], p.v[j], d2 * p.w[i] * p.w[j] * p.n * p.n.transpose());
      }
    }
    H.resize(dofs(), dofs());
    H.setFromTriplets(t.begin(), t.end());
  }

  struct FrameReport {
    int iterations = 0;
    std::size_t active = 0;
    double step_size_sum = 0;  ///< the collision-free step sizes of the frame's line searches, summed
  };

  /// The pairs near x and how far towards `target` no pair comes closer than the separation.
  auto line_search(const std::vector<Point>& x, const std::vector<Point>& target) {
    if (!step_detector) return detector.active_set_and_step(x, target, dhat, separation);
    return decltype(detector.active_set_and_step(x, target, dhat, separation)){detector.proximity(x, dhat),
                                                                               step_detector->earliest_toi(x, target)};
  }

  /// One implicit step of the cloth; v updated from the motion.
  FrameReport step(std::vector<Point>& x, std::vector<Vec3>& v) {
    xt = x;
    for (int i = 0; i < scene.cloth_vertices; ++i)
      for (int c = 0; c < 3; ++c) xt[i][c] += h * v[i][c] + h * h * gravity[c];
    const std::vector<Point> start = x;
    FrameReport report;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    Proximities near = detector.proximity(x, dhat);  // then those of each accepted trial
    for (; report.iterations < max_iterations; ++report.iterations) {
      // The Newton direction at x, from the pairs near x.
      const std::vector<BarrierPair> pairs = barrier_pairs(near, x);
      report.active = pairs.size();
      Eigen::VectorXd g;
      Eigen::SparseMatrix<double> H;
      derivatives(x, pairs, g, H);
      solver.compute(H);
      const Eigen::VectorXd dx = solver.solve(-g);
      if (dx.lpNorm<Eigen::Infinity>() < 1e-3 * h) break;  // converged: no vertex would change its speed by 1 mm/s
      // How far it may go: the collision-free step size for the separation (with the active set at x, for E(x)),
      // then backtracking on E, every trial's pairs from the proximity query.
      std::vector<Point> target = x;
      for (int i = 0; i < scene.cloth_vertices; ++i)
        for (int c = 0; c < 3; ++c) target[i][c] += dx[3 * i + c];
      if (on_newton_step) on_newton_step(x, target);
      const auto line = line_search(x, target);
      report.step_size_sum += line.step_size;
      double alpha = line.step_size >= 1 ? 1.0 : 0.9 * line.step_size;  // short of the separation, where it binds
      const double e0 = energy(x, line.active), slope = g.dot(dx);
      std::vector<Point> trial = x;
      for (int tries = 0;; ++tries) {
        for (int i = 0; i < scene.cloth_vertices; ++i)
          for (int c = 0; c < 3; ++c) trial[i][c] = x[i][c] + alpha * dx[3 * i + c];
        near = detector.proximity(trial, dhat);
        if (energy(trial, near) <= e0 + 1e-4 * alpha * slope || tries == 30) break;
        alpha /= 2;
      }
      x = trial;
    }
    for (int i = 0; i < scene.cloth_vertices; ++i) v[i] = (at(x, i) - at(start, i)) / h;
    return report;
  }
};

}  // namespace ccdlab::barrier
