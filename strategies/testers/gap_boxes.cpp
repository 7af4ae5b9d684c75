#include "strategies/testers/gap_boxes.hpp"

#include <algorithm>

namespace ccdlab::gap {

Motion Motion::of(const VertexFaceQuery& q) {
  Motion m{false, {q.v_t0, q.f0_t0, q.f1_t0, q.f2_t0}, {q.v_t1, q.f0_t1, q.f1_t1, q.f2_t1}};
  Box3 box;
  for (int k = 0; k < 4; ++k) {
    box.grow(m.x0[std::size_t(k)]);
    box.grow(m.x1[std::size_t(k)]);
    m.M = std::max({m.M, m.x0[std::size_t(k)].cwiseAbs().maxCoeff(), m.x1[std::size_t(k)].cwiseAbs().maxCoeff()});
  }
  m.L = box.extent().norm();
  return m;
}

Motion Motion::of(const EdgeEdgeQuery& q) {
  Motion m = of(VertexFaceQuery{q.ea0_t0, q.ea1_t0, q.eb0_t0, q.eb1_t0, q.ea0_t1, q.ea1_t1, q.eb0_t1, q.eb1_t1});
  m.edge_edge = true;
  return m;
}

Bilinear Motion::at(double t) const {
  std::array<Vec3, 4> p;
  for (std::size_t k = 0; k < 4; ++k) p[k] = x0[k] + t * (x1[k] - x0[k]);
  if (edge_edge) return {p[0] - p[2], p[1] - p[0], p[2] - p[3], Vec3::Zero()};
  return {p[0] - p[1], p[1] - p[2], Vec3::Zero(), p[2] - p[3]};
}

/// With u = 2⁻⁵³: a position x0 + t·(x1 − x0) at an exact t is within 7.01·u·M of its exact value and below
/// 1.01·M in size; A, P, Q, R are then within 16.1·u·M and below 2.03·M; the products by u, v, u·v (exact doubles
/// in [0, 1]) and the three sums bring the error to at most 91.3·u·M < 2⁻⁴⁶·M (fused multiply-adds only drop
/// roundings). Twice that, plus 2⁻¹⁰⁰⁰ for the few products that may underflow.
double value_error(double M) { return 0x1p-45 * M + 0x1p-1000; }

Interval around(double x, double err) { return {detail::widen_down(x - err), detail::widen_up(x + err)}; }

bool excluded_by_axes(const std::array<Vec3, 8>& F, double err, double reach) {
  for (int j = 0; j < 3; ++j) {
    double lo = F[0][j], hi = F[0][j];
    for (std::size_t i = 1; i < 8; ++i) {
      lo = std::min(lo, F[i][j]);
      hi = std::max(hi, F[i][j]);
    }
    if (around(lo, err).lo > reach || around(hi, err).hi < -reach) return true;
  }
  return false;
}

std::array<Vec3, 8> corners(const Motion& m, const Box& b) {
  const Bilinear g0 = m.at(b.t0), g1 = m.at(b.t1);
  std::array<Vec3, 8> F;
  for (int i = 0; i < 8; ++i) F[std::size_t(i)] = (i & 1 ? g1 : g0).at(i & 2 ? b.u1 : b.u0, i & 4 ? b.v1 : b.v0);
  return F;
}

std::array<double, 3> movement(const std::array<Vec3, 8>& F) {
  std::array<double, 3> move{};
  for (std::size_t i = 0; i < 8; ++i)
    for (std::size_t d = 0; d < 3; ++d)
      if (!(i & (std::size_t(1) << d))) move[d] = std::max(move[d], (F[i | (std::size_t(1) << d)] - F[i]).cwiseAbs().maxCoeff());
  return move;
}

}  // namespace ccdlab::gap
