#include "strategies/scenes/drape_fold_scene.hpp"

#include <cmath>
#include <memory>

#include <fmt/format.h>

namespace ccdlab {
namespace {

constexpr double pi = 3.14159265358979323846;

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

/// Sheet topology: (n+1)² vertices, 2n² triangles, alternating diagonals (no preferred direction).
std::vector<Face> sheet_faces(int n) {
  std::vector<Face> faces;
  faces.reserve(2 * std::size_t(n) * n);
  auto id = [n](int i, int j) { return Index(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        faces.push_back({a, b, c});
        faces.push_back({a, c, d});
      } else {
        faces.push_back({a, b, d});
        faces.push_back({b, c, d});
      }
    }
  return faces;
}

/// UV sphere of unit radius: 2 poles + (lat−1)·lon ring vertices.
void unit_sphere(int lon, Positions& x, std::vector<Face>& faces, Index offset) {
  const int lat = std::max(2, lon / 2);
  x.push_back(Vec3(0, 0, 1));
  for (int r = 1; r < lat; ++r)
    for (int s = 0; s < lon; ++s) {
      double th = pi * r / lat, ph = 2 * pi * s / lon;
      x.push_back(Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
    }
  x.push_back(Vec3(0, 0, -1));
  const Index south = Index(x.size()) - 1;  // local index, like ring()
  auto ring = [lon](int r, int s) { return Index(1 + (r - 1) * lon + (s % lon)); };
  for (int s = 0; s < lon; ++s) faces.push_back({offset, Index(offset + ring(1, s)), Index(offset + ring(1, s + 1))});
  for (int r = 1; r + 1 < lat; ++r)
    for (int s = 0; s < lon; ++s) {
      Index a = offset + ring(r, s), b = offset + ring(r + 1, s), c = offset + ring(r + 1, s + 1), d = offset + ring(r, s + 1);
      faces.push_back({a, b, c});
      faces.push_back({a, c, d});
    }
  for (int s = 0; s < lon; ++s)
    faces.push_back({Index(offset + ring(lat - 1, s + 1)), Index(offset + ring(lat - 1, s)), Index(offset + south)});
}

}  // namespace

MeshSequence make_drape_fold_scene(const DrapeFoldParams& p) {
  const int n = p.resolution;
  std::vector<Face> faces = sheet_faces(n);
  const Index sheet_vertices = Index((n + 1) * (n + 1));
  const Index sheet_faces_count = Index(faces.size());
  std::vector<Body> bodies{Body{"cloth", BodyKind::cloth, p.self_collision, 0, sheet_vertices, 0, sheet_faces_count}};

  auto sphere_rest = std::make_shared<Positions>();
  const bool has_sphere = p.sphere_radius > 0;
  if (has_sphere) {
    unit_sphere(p.sphere_segments, *sphere_rest, faces, sheet_vertices);
    bodies.push_back(Body{"sphere", BodyKind::obstacle, false, sheet_vertices, sheet_vertices + Index(sphere_rest->size()),
                          sheet_faces_count, Index(faces.size())});
  }
  const Index num_vertices = sheet_vertices + Index(sphere_rest->size());
  TriMesh topology(num_vertices, std::move(faces));

  auto source = [p, n, has_sphere, sphere_rest, num_vertices](int frame) {
    const double tau = p.frames > 1 ? double(frame) / (p.frames - 1) : 0.0;
    const double theta = p.fold_deg * pi / 180 * smoothstep(tau);
    const double rho = p.crease_radius;
    const double R = p.sphere_radius;
    const Vec3 center(p.sphere_travel * (2 * tau - 1), 0, -0.6 * R);
    const double gap = 0.02 * R;
    Positions x(num_vertices);
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double u = -1 + 2.0 * i / n, v = -1 + 2.0 * j / n;
        const double w = p.wrinkle != 0 ? p.wrinkle * std::sin(4 * pi * v) * std::cos(3 * pi * u) : 0.0;
        Vec3 q(u, v, w);
        if (theta > 0 && u > p.crease) {
          // Fold: arc length s from the crease maps onto the round crease, then the straight flap.
          const double s = u - p.crease;
          double phi = std::min(s / rho, theta);
          Vec3 base(p.crease + rho * std::sin(phi), v, rho * (1 - std::cos(phi)));
          Vec3 tangent(std::cos(phi), 0, std::sin(phi)), normal(-std::sin(phi), 0, std::cos(phi));
          q = base + std::max(0.0, s - rho * theta) * tangent + w * normal;
        }
        if (has_sphere) {
          // Drape: the sheet rests on the sphere cap that rises above z = 0.
          const double d2 = (q.x() - center.x()) * (q.x() - center.x()) + q.y() * q.y();
          const double cap = d2 < R * R ? std::max(0.0, std::sqrt(R * R - d2) + center.z()) : 0.0;
          q.z() += cap + gap;
        }
        x[j * (n + 1) + i] = q;
      }
    if (has_sphere)
      for (std::size_t k = 0; k < sphere_rest->size(); ++k) x[(n + 1) * (n + 1) + k] = center + R * (*sphere_rest)[k];
    return x;
  };
  std::vector<std::string> labels;
  for (int f = 0; f < p.frames; ++f) labels.push_back(std::to_string(f));
  std::string desc = fmt::format("drape_fold: {} cloth triangles{}, {} frames", 2 * n * n,
                                 has_sphere ? fmt::format(" + sphere ({} triangles)", topology.num_faces() - 2 * n * n) : "",
                                 p.frames);
  return MeshSequence(std::move(topology), std::move(bodies), std::move(labels), std::move(source), std::move(desc));
}

}  // namespace ccdlab
