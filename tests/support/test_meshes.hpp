#pragma once
// Small meshes made in code for tests: grids, random deformations and motions, and the shared-data path.
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "framework/mesh/mesh_io.hpp"
#include "framework/pipeline/bodies.hpp"

namespace ccdlab::test {

/// An n×m grid of squares in the xy-plane, [0, 1]², two triangles per square.
inline MeshData grid(int n, int m) {
  MeshData g;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) g.positions.emplace_back(double(i) / n, double(j) / m, 0.0);
  auto id = [n](int i, int j) { return Index(j * (n + 1) + i); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      g.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      g.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return g;
}

/// A crumpled random frame: the grid folded by a random smooth map plus noise, so that distant parts of the
/// sheet come close (self-contacts) — the stress case for broad and narrow phase.
inline Positions crumple(const Positions& rest, std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-1, 1);
  const double a = u(rng) * 3, b = u(rng) * 3, c = u(rng) * 6, d = u(rng);
  Positions x = rest;
  for (Vec3& p : x) {
    const double s = p.x(), t = p.y();
    Vec3 q(std::sin(a * s + d) * 0.5 + s * 0.3, t + 0.1 * std::cos(b * s), 0.4 * std::sin(c * s * t + d));
    p = q + amplitude * Vec3(u(rng), u(rng), u(rng));
  }
  return x;
}

/// Concatenates two meshes into one MeshData (second's vertex ids offset).
inline MeshData concat(const MeshData& a, const MeshData& b) {
  MeshData out = a;
  const Index off = Index(a.positions.size());
  out.positions.insert(out.positions.end(), b.positions.begin(), b.positions.end());
  for (Face f : b.faces) out.faces.push_back({f[0] + off, f[1] + off, f[2] + off});
  return out;
}

/// ../shared/data, or "" when absent (tests then GTEST_SKIP with a message).
inline std::string shared_data() {
  if (const char* env = std::getenv("CCDLAB_SHARED_DATA")) return env;
  std::string p = CCDLAB_SHARED_DATA;
  return std::filesystem::exists(p) ? p : "";
}

/// A fresh temporary directory for a test.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("ccdlab_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace ccdlab::test
