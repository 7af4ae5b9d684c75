#include "framework/narrow/split_filter.hpp"

#include <algorithm>
#include <cmath>

namespace ccdlab {
namespace {

constexpr double u = 0x1p-53;
/// Windows down to 1/16 of the step: deeper ones rarely pay for their boxes.
constexpr int kMaxDepth = 4;
static_assert(kMaxDepth <= 8, "the rounding bound below covers 8 halvings");


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
                        const PlaneBatch& plane, std::size_t row) {
  const std::array<double, 4> b = {plane.result(PlaneBatch::Q0, row), plane.result(PlaneBatch::Q1x3, row) / 3,
                                   plane.result(PlaneBatch::Q2x3, row) / 3, plane.result(PlaneBatch::Q3, row)};
  double M = 0;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) M = std::max({M, std::abs((*p0[i])[k]), std::abs((*p1[i])[k])});
  const double bmax = std::max({std::abs(b[0]), std::abs(b[1]), std::abs(b[2]), std::abs(b[3])});
  // Stage 2's threshold, + u·max|b| for the division by 3 and 2u·max|b| per halving (kMaxDepth ≤ 8 of them).
  const double t = plane.result(PlaneBatch::Threshold, row) * (1 + 4 * u) + 18 * u * bmax;
  const double pad = plane.result(PlaneBatch::Reach, row) * (1 + 1e-12) + 8 * u * M + 1e-300;
  const int split = vf ? 1 : 2;  // first feature = points [0, split), second = [split, 4)
  // Positions at t: x0 + t·d, per point and axis, in plain arrays (the window loop below runs often).
  double x0[4][3], d[4][3];
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) x0[i][k] = (*p0[i])[k], d[i][k] = (*p1[i])[k] - (*p0[i])[k];
  // No contact within the reach in [ta, tb] (c: f's Bernstein coefficients there) when f keeps its sign or the
  // features' boxes are apart; otherwise halve, down to kMaxDepth. Depth first, on an explicit stack.
  struct Window {
    double ta, tb;
    std::array<double, 4> c;
    int depth;
  };
  std::array<Window, 2 * kMaxDepth + 2> stack;
  int top = 0;
  std::array<double, 4> l, h;
  halve(b, l, h);  // the whole step failed stages 1 and 2 already
  stack[top++] = {0.5, 1.0, h, 1};
  stack[top++] = {0.0, 0.5, l, 1};
  while (top > 0) {
    const Window w = stack[--top];
    const auto& c = w.c;
    const bool above = c[0] > t && c[1] > t && c[2] > t && c[3] > t;
    const bool below = c[0] < -t && c[1] < -t && c[2] < -t && c[3] < -t;
    if (above || below) continue;
    bool apart = false;
    for (int k = 0; k < 3 && !apart; ++k) {
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      for (int i = 0; i < 4; ++i) {
        const int f = i < split ? 0 : 1;
        const double xa = x0[i][k] + w.ta * d[i][k], xb = x0[i][k] + w.tb * d[i][k];
        lo[f] = std::min({lo[f], xa, xb});
        hi[f] = std::max({hi[f], xa, xb});
      }
      apart = lo[0] - pad > hi[1] || lo[1] - pad > hi[0];
    }
    if (apart) continue;
    if (w.depth == kMaxDepth) return true;
    halve(c, l, h);
    const double tm = 0.5 * (w.ta + w.tb);
    stack[top++] = {tm, w.tb, h, w.depth + 1};
    stack[top++] = {w.ta, tm, l, w.depth + 1};
  }
  return false;
}

}  // namespace ccdlab