#include "framework/geometry/kdop_polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace ccdlab {

Polyhedron slab_polyhedron(std::span<const std::array<int, 3>> axes, std::span<const float> min,
                           std::span<const float> max) {
  struct Plane {
    Vec3 n;    // outward normal (an axis or its opposite, not normalised)
    double c;  // n · x ≤ c inside
  };
  std::vector<Plane> planes;
  double scale = 0;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (!(double(min[i]) <= double(max[i])) || !std::isfinite(min[i]) || !std::isfinite(max[i])) return {};
    const Vec3 d(axes[i][0], axes[i][1], axes[i][2]);
    planes.push_back({d, double(max[i])});
    planes.push_back({-d, -double(min[i])});
    scale = std::max({scale, std::abs(double(min[i])), std::abs(double(max[i]))});
  }
  // Which planes a vertex lies on is decided by how it was made — the planes whose intersection it is — not by
  // a distance test. Points closer than 1e-6 of the coordinates' size are one vertex, lying on every plane of
  // every triple that made it: the bounds are floats (spacing 6e-8 relative), and slivers a few float steps
  // wide, where a slab grazes an edge or a corner by one rounding of its bound, say nothing the bounds can
  // resolve; merged, they become edges or corners and the surface stays closed. Invisible in any picture.
  const double tol = 1e-6 * std::max(scale, 1e-30);

  Polyhedron out;
  std::vector<std::uint32_t> on_planes;  // bit j: the vertex lies on plane j (K ≤ 26 planes)
  auto add_vertex = [&](const Vec3& p, std::uint32_t planes_mask) {
    for (std::size_t v = 0; v < out.vertices.size(); ++v)
      if ((out.vertices[v] - p).lpNorm<Eigen::Infinity>() <= tol) {
        on_planes[v] |= planes_mask;
        return;
      }
    out.vertices.push_back(p);
    on_planes.push_back(planes_mask);
  };
  auto inside = [&](const Vec3& p) {
    for (const Plane& q : planes)
      if (q.n.dot(p) > q.c + 1e-3 * tol * q.n.lpNorm<1>()) return false;  // rounding of the solve only
    return true;
  };
  const std::size_t n = planes.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        const Vec3 jk = planes[j].n.cross(planes[k].n), ki = planes[k].n.cross(planes[i].n),
                   ij = planes[i].n.cross(planes[j].n);
        const double det = planes[i].n.dot(jk);  // integer normals: 0 exactly when the three are dependent
        if (det == 0) continue;
        const Vec3 p = (planes[i].c * jk + planes[j].c * ki + planes[k].c * ij) / det;
        if (inside(p)) add_vertex(p, (1u << i) | (1u << j) | (1u << k));
      }

  for (std::size_t j = 0; j < n; ++j) {
    const Plane& q = planes[j];
    std::vector<int> on;
    for (std::size_t v = 0; v < out.vertices.size(); ++v)
      if (on_planes[v] >> j & 1u) on.push_back(int(v));
    if (on.size() < 3) continue;  // the slab touches the solid in an edge or a vertex only
    // The face is the convex hull of those vertices in the plane (monotone chain, counter-clockwise about the
    // outward normal). Collinear points — a vertex where another slab grazes an edge — are dropped, in every
    // face alike, so the surface stays closed; a slab touching only along an edge gives a hull of 2: no face.
    const Vec3 normal = q.n.normalized();
    const Vec3 u = (std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(normal).normalized();
    const Vec3 w = normal.cross(u);
    std::vector<std::pair<std::pair<double, double>, int>> pts;
    for (int v : on) pts.push_back({{out.vertices[v].dot(u), out.vertices[v].dot(w)}, v});
    std::sort(pts.begin(), pts.end());
    const double area_tol = 1e-18 * std::max(scale * scale, 1e-300);
    auto turn = [&](const auto& o, const auto& a, const auto& b) {
      return (a.first.first - o.first.first) * (b.first.second - o.first.second) -
             (a.first.second - o.first.second) * (b.first.first - o.first.first);
    };
    std::vector<std::pair<std::pair<double, double>, int>> hull;
    for (int pass = 0; pass < 2; ++pass) {
      const std::size_t start = hull.size();
      for (const auto& p : pts) {
        while (hull.size() >= start + 2 && turn(hull[hull.size() - 2], hull.back(), p) <= area_tol) hull.pop_back();
        hull.push_back(p);
      }
      hull.pop_back();  // the last point of one chain is the first of the other
      std::reverse(pts.begin(), pts.end());
    }
    if (hull.size() < 3) continue;
    std::vector<int> face;
    for (const auto& p : hull) face.push_back(p.second);
    out.faces.push_back(std::move(face));
  }
  // Drop vertices no face uses (grazing points removed above).
  std::vector<int> remap(out.vertices.size(), -1);
  std::vector<Vec3> used;
  for (auto& face : out.faces)
    for (int& v : face) {
      if (remap[std::size_t(v)] < 0) remap[std::size_t(v)] = int(used.size()), used.push_back(out.vertices[std::size_t(v)]);
      v = remap[std::size_t(v)];
    }
  out.vertices = std::move(used);
  return out;
}

}  // namespace ccdlab
