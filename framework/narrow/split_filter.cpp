#include "framework/narrow/split_filter.hpp"

#include <algorithm>
#include <cmath>

namespace ccdlab {
namespace {

constexpr double u = 0x1p-53;
/// Windows down to 1/16 of the step: deeper ones rarely pay for their boxes.
constexpr int kMaxDepth = 4;
static_assert(kMaxDepth <= 8, "the rounding bound below covers 8 halvings");

double det(const Vec3& x, const Vec3& y, const Vec3& z) {
  const Vec3 c(y.y() * z.z() - y.z() * z.y(), y.z() * z.x() - y.x() * z.z(), y.x() * z.y() - y.y() * z.x());
  return (x.x() * c.x() + x.y() * c.y()) + x.z() * c.z();
}
double norm1(const Vec3& x) { return std::abs(x.x()) + std::abs(x.y()) + std::abs(x.z()); }

/// Bernstein coefficients of a cubic on [0, 1/2] and [1/2, 1] (de Casteljau at 1/2; halvings are exact but
/// for the sums' rounding).
void halve(const std::array<double, 4>& b, std::array<double, 4>& lo, std::array<double, 4>& hi) {
  const double b01 = 0.5 * (b[0] + b[1]), b12 = 0.5 * (b[1] + b[2]), b23 = 0.5 * (b[2] + b[3]);
  const double b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23), mid = 0.5 * (b012 + b123);
  lo = {b[0], b01, b012, mid};
  hi = {mid, b123, b23, b[3]};
}

}  // namespace

bool split_filter_keeps(bool vf, const std::array<const Vec3*, 4>& p0, const std::array<const Vec3*, 4>& p1,
                        CullReach reach) {
  // A, B, C of plane_filter.hpp at both ends.
  const auto abc = [&](const std::array<const Vec3*, 4>& p, Vec3& A, Vec3& B, Vec3& C) {
    if (vf) A = *p[0] - *p[1], B = *p[2] - *p[1], C = *p[3] - *p[1];
    else A = *p[2] - *p[0], B = *p[1] - *p[0], C = *p[3] - *p[2];
  };
  Vec3 A0, B0, C0, A1, B1, C1;
  abc(p0, A0, B0, C0);
  abc(p1, A1, B1, C1);
  const std::array<double, 4> b = {det(A0, B0, C0), (det(A1, B0, C0) + det(A0, B1, C0) + det(A0, B0, C1)) / 3,
                                   (det(A0, B1, C1) + det(A1, B0, C1) + det(A1, B1, C0)) / 3, det(A1, B1, C1)};
  double M = 0, L = 0;
  for (int i = 0; i < 4; ++i) M = std::max({M, p0[i]->cwiseAbs().maxCoeff(), p1[i]->cwiseAbs().maxCoeff()});
  L = 2 * std::sqrt(3.0) * M;  // every coordinate within ±M: the pair's extent is at most that diagonal
  const double r = reach.abs + reach.rel * L;
  const double ma = std::max(norm1(A0), norm1(A1)), mb = std::max(norm1(B0), norm1(B1)),
               mc = std::max(norm1(C0), norm1(C1));
  const double bmax = std::max({std::abs(b[0]), std::abs(b[1]), std::abs(b[2]), std::abs(b[3])});
  const double bc = std::sqrt(std::max(B0.squaredNorm(), B1.squaredNorm()) * std::max(C0.squaredNorm(), C1.squaredNorm()));
  // 32u for the coefficients (+4u for the division by 3), 2u·max|b| per halving (kMaxDepth ≤ 8 of them).
  const double t = r * bc * (1 + 1e-12) + 40 * u * (ma * mb * mc) + 16 * u * bmax + 1e-290;
  const double pad = r * (1 + 1e-12) + 8 * u * M + 1e-300;
  const int split = vf ? 1 : 2;  // first feature = points [0, split), second = [split, 4)
  auto at = [&](int i, double s) -> Vec3 { return *p0[i] + s * (*p1[i] - *p0[i]); };
  // True when no contact within the reach is possible in [ta, tb] (c: f's Bernstein coefficients there).
  auto apart = [&](auto&& self, double ta, double tb, const std::array<double, 4>& c, int depth) -> bool {
    const bool above = c[0] > t && c[1] > t && c[2] > t && c[3] > t;
    const bool below = c[0] < -t && c[1] < -t && c[2] < -t && c[3] < -t;
    if (above || below) return true;
    Vec3 lo[2] = {Vec3::Constant(INFINITY), Vec3::Constant(INFINITY)};
    Vec3 hi[2] = {Vec3::Constant(-INFINITY), Vec3::Constant(-INFINITY)};
    for (int i = 0; i < 4; ++i) {
      const int f = i < split ? 0 : 1;
      for (double s : {ta, tb}) {
        const Vec3 x = at(i, s);
        lo[f] = lo[f].cwiseMin(x);
        hi[f] = hi[f].cwiseMax(x);
      }
    }
    if (((lo[0].array() - pad > hi[1].array()) || (lo[1].array() - pad > hi[0].array())).any()) return true;
    if (depth == kMaxDepth) return false;
    std::array<double, 4> l, h;
    halve(c, l, h);
    const double tm = 0.5 * (ta + tb);
    return self(self, ta, tm, l, depth + 1) && self(self, tm, tb, h, depth + 1);
  };
  std::array<double, 4> l, h;
  halve(b, l, h);  // the whole step failed stages 1 and 2 already
  return !(apart(apart, 0.0, 0.5, l, 1) && apart(apart, 0.5, 1.0, h, 1));
}

}  // namespace ccdlab