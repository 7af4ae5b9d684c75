// A 24×24 mass-spring cloth falls onto a square floor (an obstacle). Each frame proposes explicit spring-and-
// gravity motion; Detector::earliest_toi says how far the cloth can go before a contact, and the frame takes 90%
// of that (the vertices lose speed when cut short; those resting on the floor lose their speed into it): no
// frame ever ends in a collision.
#include <ccdlab/ccdlab.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

int main() try {
  const int n = 24;  // vertices per side; spacing h
  const double h = 1.0 / (n - 1), dt = 2e-3, stiffness = 4e3, gravity = -9.81;
  std::vector<ccdlab::Point> x;        // the cloth's vertices, then the floor's four
  std::vector<ccdlab::Triangle> cloth, floor{{0, 1, 2}, {0, 2, 3}};
  std::vector<std::array<int, 2>> springs;  // structural springs along the grid
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      x.push_back({i * h, j * h, 0.3 + 0.2 * i * h});  // tilted: one side lands first
      if (i + 1 < n) springs.push_back({j * n + i, j * n + i + 1});
      if (j + 1 < n) springs.push_back({j * n + i, (j + 1) * n + i});
      if (i + 1 < n && j + 1 < n) {
        cloth.push_back({j * n + i, j * n + i + 1, (j + 1) * n + i + 1});
        cloth.push_back({j * n + i, (j + 1) * n + i + 1, (j + 1) * n + i});
      }
    }
  for (const ccdlab::Point& p : {ccdlab::Point{-1, -1, 0}, {2, -1, 0}, {2, 2, 0}, {-1, 2, 0}}) x.push_back(p);
  const int cloth_vertices = n * n;
  const std::vector<ccdlab::Detector::Body> bodies{{cloth, cloth_vertices, false, true, "cloth"},
                                                   {floor, 4, true, false, "floor"}};
  ccdlab::Detector detector(bodies, ccdlab::Options::from_yaml("{tester: exact, scheduler: phc, threads: 2}"));

  std::vector<ccdlab::Point> v(x.size(), {0, 0, 0}), next = x;
  for (int frame = 0; frame < 300; ++frame) {
    std::vector<ccdlab::Point> f(x.size(), {0, 0, gravity});  // unit masses
    for (const auto& [a, b] : springs) {
      double d[3], len = 0;
      for (int k = 0; k < 3; ++k) d[k] = x[b][k] - x[a][k], len += d[k] * d[k];
      len = std::sqrt(len);
      for (int k = 0; k < 3; ++k) f[a][k] += stiffness * (len - h) * d[k] / len, f[b][k] -= stiffness * (len - h) * d[k] / len;
    }
    for (int i = 0; i < cloth_vertices; ++i) {
      for (int k = 0; k < 3; ++k) v[i][k] = 0.999 * (v[i][k] + dt * f[i][k]);
      if (x[i][2] < 1e-3 && v[i][2] < 0) v[i][2] = 0;  // resting on the floor: no speed into it
      for (int k = 0; k < 3; ++k) next[i][k] = x[i][k] + dt * v[i][k];
    }
    const double t = detector.earliest_toi(x, next);  // 1: the whole move is free
    const double s = t < 1 ? 0.9 * t : 1.0;
    for (int i = 0; i < cloth_vertices; ++i)
      for (int k = 0; k < 3; ++k) {
        x[i][k] += s * (next[i][k] - x[i][k]);
        if (t < 1) v[i][k] *= s;
      }
    if (frame % 50 == 0 || (t < 1 && frame % 10 == 0))
      std::printf("frame %3d: earliest time of impact %.4f, lowest cloth point z = %.5f\n", frame, t, [&] {
        double z = 1e9;
        for (int i = 0; i < cloth_vertices; ++i) z = std::min(z, x[i][2]);
        return z;
      }());
  }
  return 0;
} catch (const ccdlab::Error& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}
