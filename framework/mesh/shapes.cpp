#include "framework/mesh/shapes.hpp"

#include <cmath>

#include "framework/util/error.hpp"

namespace ccdlab {

void append_sheet(MeshData& m, const Vec3& centre, double size_x, double size_z, int cells_x, int cells_z) {
  if (cells_x < 1 || cells_z < 1) fail("sheet: expected at least 1 cell per side, got {} × {}", cells_x, cells_z);
  const Index base = Index(m.positions.size());
  for (int j = 0; j <= cells_z; ++j)
    for (int i = 0; i <= cells_x; ++i)
      m.positions.emplace_back(centre.x() + size_x * (double(i) / cells_x - 0.5), centre.y(),
                               centre.z() + size_z * (double(j) / cells_z - 0.5));
  auto id = [&](int i, int j) { return base + Index(j * (cells_x + 1) + i); };
  for (int j = 0; j < cells_z; ++j)
    for (int i = 0; i < cells_x; ++i) {
      const Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.faces.push_back({a, c, b});
        m.faces.push_back({a, d, c});
      } else {
        m.faces.push_back({a, d, b});
        m.faces.push_back({b, d, c});
      }
    }
}

namespace {

/// Rings of points around an axis (rows of `segments`), joined into quads (two triangles each).
void join_rings(MeshData& m, Index first, int rings, int segments) {
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const Index a = first + Index(r * segments + s), b = first + Index(r * segments + (s + 1) % segments);
      const Index c = a + Index(segments), d = b + Index(segments);
      m.faces.push_back({a, c, b});
      m.faces.push_back({b, c, d});
    }
}

}  // namespace

void append_sphere(MeshData& m, const Vec3& centre, double radius, int segments) {
  if (segments < 4) fail("sphere: expected at least 4 segments, got {}", segments);
  const int rings = segments + 1;  // latitude lines from pole to pole, the two poles single points
  const Index top = Index(m.positions.size());
  m.positions.push_back(centre + Vec3(0, radius, 0));
  const Index first = Index(m.positions.size());
  for (int r = 1; r + 1 < rings; ++r) {
    const double theta = M_PI * r / (rings - 1);
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      m.positions.push_back(centre + radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  }
  const Index bottom = Index(m.positions.size());
  m.positions.push_back(centre - Vec3(0, radius, 0));
  for (int s = 0; s < segments; ++s) m.faces.push_back({top, first + Index((s + 1) % segments), first + Index(s)});
  join_rings(m, first, rings - 2, segments);
  const Index last = first + Index((rings - 3) * segments);
  for (int s = 0; s < segments; ++s) m.faces.push_back({bottom, last + Index(s), last + Index((s + 1) % segments)});
}

void append_capsule(MeshData& m, const Vec3& a, const Vec3& b, double radius, int segments) {
  if (segments < 4) fail("capsule: expected at least 4 segments, got {}", segments);
  const Vec3 axis = (b - a).normalized();
  const Vec3 u = (std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(axis).normalized(), w = axis.cross(u);
  const int cap_rings = std::max(2, segments / 4);
  const Index tip_b = Index(m.positions.size());
  m.positions.push_back(b + radius * axis);
  const Index first = Index(m.positions.size());
  // Rings from the b cap down to the a cap: cap_rings on each hemisphere (the equators included).
  int rings = 0;
  for (int side = 0; side < 2; ++side)
    for (int r = 0; r < cap_rings; ++r) {
      const double theta = M_PI / 2 * (side == 0 ? double(r + 1) / cap_rings : 1 - double(r) / cap_rings);
      const Vec3 end = side == 0 ? b : a;
      const double along = (side == 0 ? 1 : -1) * radius * std::cos(theta), around = radius * std::sin(theta);
      for (int s = 0; s < segments; ++s) {
        const double phi = 2 * M_PI * s / segments;
        m.positions.push_back(end + along * axis + around * (std::cos(phi) * u + std::sin(phi) * w));
      }
      ++rings;
    }
  const Index tip_a = Index(m.positions.size());
  m.positions.push_back(a - radius * axis);
  for (int s = 0; s < segments; ++s) m.faces.push_back({tip_b, first + Index(s), first + Index((s + 1) % segments)});
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const Index p = first + Index(r * segments + s), q = first + Index(r * segments + (s + 1) % segments);
      m.faces.push_back({p, p + Index(segments), q});
      m.faces.push_back({q, p + Index(segments), q + Index(segments)});
    }
  const Index last = first + Index((rings - 1) * segments);
  for (int s = 0; s < segments; ++s) m.faces.push_back({tip_a, last + Index((s + 1) % segments), last + Index(s)});
}

void append_frustum(MeshData& m, const Vec3& centre, double r_top, double r_bottom, double height, int segments, int rows) {
  if (segments < 3 || rows < 1) fail("frustum: expected at least 3 segments and 1 row, got {} and {}", segments, rows);
  const Index first = Index(m.positions.size());
  for (int r = 0; r <= rows; ++r) {
    const double t = double(r) / rows, radius = (1 - t) * r_top + t * r_bottom;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      m.positions.push_back(centre + Vec3(radius * std::cos(phi), height / 2 - t * height, radius * std::sin(phi)));
    }
  }
  join_rings(m, first, rows + 1, segments);
}

}  // namespace ccdlab
