#include "framework/narrow/proximity_filter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "framework/geometry/distance.hpp"

namespace ccdlab {
namespace {

constexpr double kU = 0x1p-53;
constexpr double kSlack = 128 * kU;    // relative to M: positions at the window's middle, projections, columns
constexpr double kFactor = 1 + 1e-12;  // on the speed and the reach

Vec3 point(const PlaneBatch& b, int column, std::size_t i) {
  return {b.column(column)[i], b.column(column + 1)[i], b.column(column + 2)[i]};
}

}  // namespace

bool proximity_filter_keeps(const PlaneBatch& plane, std::size_t i, bool vf, std::uint16_t open, int levels) {
  const Vec3 a0 = point(plane, PlaneBatch::A0x, i), b0 = point(plane, PlaneBatch::B0x, i),
             c0 = point(plane, PlaneBatch::C0x, i);
  const Vec3 ma = point(plane, PlaneBatch::A1x, i) - a0, mb = point(plane, PlaneBatch::B1x, i) - b0,
             mc = point(plane, PlaneBatch::C1x, i) - c0;
  double M = 0;
  for (const int c : {PlaneBatch::A0x, PlaneBatch::A1x, PlaneBatch::B0x, PlaneBatch::B1x, PlaneBatch::C0x, PlaneBatch::C1x})
    for (int k = 0; k < 3; ++k) M = std::max(M, std::abs(plane.column(c + k)[i]));
  // VF: vertex A against face {0, B, C}; EE: edge {0, B} against edge {A, A + C} (stage 2's frame).
  const double speed = vf ? std::max({ma.norm(), (ma - mb).norm(), (ma - mc).norm()})
                          : std::max({ma.norm(), (ma + mc).norm(), (ma - mb).norm(), (ma + mc - mb).norm()});
  const int windows = 1 << levels;
  const double half_width = 0.5 / windows;
  const double need = plane.result(PlaneBatch::Reach, i) * kFactor + speed * half_width * kFactor + kSlack * M;
  for (unsigned bits = open; bits != 0; bits &= bits - 1) {
    const double t = (std::countr_zero(bits) + 0.5) / windows;
    const Vec3 a = a0 + t * ma, b = b0 + t * mb, c = c0 + t * mc;
    double gap;
    if (vf) {
      const PointTriangleClosest cp = closest_point_triangle(a, Vec3::Zero(), b, c);
      Vec3 u = a - (cp.bary[1] * b + cp.bary[2] * c);
      const double n = u.norm();
      if (!(n > 0)) return true;
      u /= n;
      gap = u.dot(a) - std::max({0.0, u.dot(b), u.dot(c)});
    } else {
      const Vec3 e = a + c;
      const SegmentSegmentClosest cs = closest_segment_segment(Vec3::Zero(), b, a, e);
      Vec3 u = (a + cs.t * c) - cs.s * b;
      const double n = u.norm();
      if (!(n > 0)) return true;
      u /= n;
      gap = std::min(u.dot(a), u.dot(e)) - std::max(0.0, u.dot(b));
    }
    if (!(gap > need)) return true;
  }
  return false;
}

}  // namespace ccdlab
