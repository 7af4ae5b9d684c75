#include "strategies/testers/float_tester.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "framework/geometry/distance.hpp"
#include "strategies/testers/float_roots.hpp"

namespace ccdlab {
namespace {

/// A point moving linearly: x(t) = x0 + t·dx.
struct Moving {
  Vec3 x0, dx;
  [[nodiscard]] Vec3 at(double t) const { return x0 + t * dx; }
  Moving operator-(const Moving& o) const { return {x0 - o.x0, dx - o.dx}; }
};

/// A short list of candidate times, without heap allocation (at most 2 + 3 + 3 + 16 entries are pushed).
struct TimeList {
  std::array<double, 32> v;
  std::size_t n = 0;
  void push_back(double t) {
    if (n < v.size()) v[n++] = t;
  }
  [[nodiscard]] std::size_t size() const { return n; }
  double& operator[](std::size_t i) { return v[i]; }
  double* begin() { return v.data(); }
  double* end() { return v.data() + n; }
};

/// Appends the roots in [0, 1] of a t² + b t + c (numerically stable form).
void quadratic_roots(double a, double b, double c, TimeList& all) {
  TimeList out;
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(c)});
  if (scale == 0) return;
  if (std::abs(a) <= 1e-14 * scale) {
    if (std::abs(b) > 1e-14 * scale) out.push_back(-c / b);
  } else {
    double disc = b * b - 4 * a * c;
    if (disc < 0) {
      if (disc > -1e-12 * b * b) disc = 0; else return;
    }
    double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    out.push_back(q / a);
    if (q != 0) out.push_back(c / q);
  }
  for (double t : out)
    if (t >= 0 && t <= 1) all.push_back(t);
}

/// A query's four points at t0, then the same four at t1.
using QueryPoints = std::array<const Vec3*, 8>;

/// Bounding-box diagonal of the query's points at t0 and t1: the length every tolerance is relative to.
double extent(const QueryPoints& pts) {
  Box3 b;
  for (const Vec3* p : pts) b.grow(*p);
  return b.extent().norm();
}

/// Point k of the query, moving, relative to `origin` (one of the points at t0: less cancellation).
Moving moving(const QueryPoints& p, int k, const Vec3& origin) { return {*p[k] - origin, *p[k + 4] - *p[k]}; }

/// The candidate times of contact in increasing order, each offered to `hit(t)` until one returns true; returns
/// whether one did. The candidates: t = 0 and t = 1 with thickness, the roots of f(t) = A(t)·(B(t)×C(t)) in
/// [0, 1], and values of t where f touches zero at a critical point. f is evaluated from the positions at t (not
/// from the expanded coefficients), which is more accurate near the roots. A root is refined only once every
/// earlier candidate has missed: the roots after a contact cost nothing (the refinement is nearly all of this
/// tester's time; the first hit, hence the answer, is the one the full sorted list gives).
/// When f ≡ 0 (coplanar motion), sets `degenerate` and offers nothing: the caller looks for crossings instead.
template <class F, class Hit>
bool earliest_hit(const Moving& A, const Moving& B, const Moving& C, F&& f, double f_scale, bool thick,
                  bool& degenerate, Hit&& hit) {
  const Vec3 &A0 = A.x0, &dA = A.dx, &B0 = B.x0, &dB = B.dx, &C0 = C.x0, &dC = C.dx;
  const double d = A0.dot(B0.cross(C0));
  const double c = dA.dot(B0.cross(C0)) + A0.dot(dB.cross(C0)) + A0.dot(B0.cross(dC));
  const double b = dA.dot(dB.cross(C0)) + dA.dot(B0.cross(dC)) + A0.dot(dB.cross(dC));
  const double a = dA.dot(dB.cross(dC));
  degenerate = std::max({std::abs(a), std::abs(b), std::abs(c), std::abs(d)}) <= 1e-12 * f_scale;
  if (degenerate) return false;
  // With thickness, contact needs no coplanarity: the ends of the step are always candidates. Without it, they
  // are candidates only when (nearly) coplanar, which the breakpoint check below finds.
  if (thick && hit(0.0)) return true;
  const double zero = FloatTester::rel_tolerance * f_scale;  // |f| ≈ distance × area: within the tolerance
  if (!thick) {
    // Early out: on [0, 1], f is a convex combination of its Bernstein coefficients, so when all four lie
    // beyond ±zero on one side, f has no root and no touching point — the answer the root search below
    // would reach (rounding of the coefficients is ~1e-15·f_scale, far inside `zero`).
    const double b0 = d, b1 = d + c / 3, b2 = d + (2 * c + b) / 3, b3 = d + c + b + a;
    if ((b0 > zero && b1 > zero && b2 > zero && b3 > zero) || (b0 < -zero && b1 < -zero && b2 < -zero && b3 < -zero))
      return false;
  }
  TimeList breaks;
  breaks.push_back(0);
  breaks.push_back(1);
  quadratic_roots(3 * a, 2 * b, c, breaks);
  std::sort(breaks.begin(), breaks.end());
  std::array<double, 4> values;
  for (std::size_t i = 0; i < breaks.size(); ++i) values[i] = f(breaks[i]);
  // In increasing order: each breakpoint where f touches zero (a double root), then the root f has between it
  // and the next one (f is monotone there).
  for (std::size_t i = 0; i < breaks.size(); ++i) {
    if (std::abs(values[i]) <= zero && hit(breaks[i])) return true;
    if (i + 1 == breaks.size()) break;
    double lo = breaks[i], hi = breaks[i + 1], flo = values[i], fhi = values[i + 1];
    if (!((flo < 0 && fhi > 0) || (flo > 0 && fhi < 0))) continue;
    // Illinois false position: monotone on [lo, hi], one root.
    int side = 0;
    double t = lo;
    for (int it = 0; it < kIllinoisSteps && hi - lo > kIllinoisWidth; ++it) {
      t = (lo * fhi - hi * flo) / (fhi - flo);
      if (!(t >= lo && t <= hi)) t = 0.5 * (lo + hi);  // NaN, or outside by rounding
      t = std::min(std::max(t, lo + kIllinoisGuard), hi - kIllinoisGuard);
      double ft = f(t);
      if (ft == 0) { lo = hi = t; break; }
      if ((ft < 0) == (flo < 0)) {
        lo = t, flo = ft;
        if (side == -1) fhi *= 0.5;
        side = -1;
      } else {
        hi = t, fhi = ft;
        if (side == 1) flo *= 0.5;
        side = 1;
      }
    }
    if (hit(0.5 * (lo + hi))) return true;
  }
  return thick && hit(1.0);
}

/// Coplanar motion: times where point p crosses the line (a, b), from the in-plane component along n.
void crossing_times(const Moving& p, const Moving& a, const Moving& b, const Vec3& n, TimeList& times) {
  // g(t) = n · ((p - a) × (b - a)), a quadratic in t.
  const Vec3 r0 = p.x0 - a.x0, dr = p.dx - a.dx, e0 = b.x0 - a.x0, de = b.dx - a.dx;
  const double c = n.dot(r0.cross(e0));
  const double bq = n.dot(dr.cross(e0) + r0.cross(de));
  const double aq = n.dot(dr.cross(de));
  quadratic_roots(aq, bq, c, times);
}

/// Coplanar motion (f ≡ 0): the ends of the step and the times `crossings` adds (where a point crosses a line
/// in the plane), offered to `hit(t)` in increasing order until one returns true.
template <class Crossings, class Hit>
void offer_coplanar_times(Crossings&& crossings, Hit&& hit) {
  TimeList times;
  times.push_back(0);
  times.push_back(1);
  crossings(times);
  std::sort(times.begin(), times.end());
  const double* end = std::unique(times.begin(), times.end());  // a time offered twice misses twice
  for (const double* t = times.begin(); t != end; ++t)
    if (hit(*t)) return;
}

/// The most reliable normal of the plane holding these points (largest cross product of differences).
Vec3 plane_normal(const std::array<Vec3, 4>& p) {
  Vec3 best = Vec3::Zero();
  for (int i = 1; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      Vec3 n = (p[i] - p[0]).cross(p[j] - p[0]);
      if (n.squaredNorm() > best.squaredNorm()) best = n;
    }
  if (best.squaredNorm() == 0) {  // all collinear (or coincident): any normal of the line
    Vec3 d = Vec3::Zero();
    for (int i = 1; i < 4; ++i) if ((p[i] - p[0]).squaredNorm() > d.squaredNorm()) d = p[i] - p[0];
    best = d.squaredNorm() > 0 ? d.unitOrthogonal() : Vec3::UnitZ();
  }
  return best;
}

/// A query relative to one of its points (less cancellation): its four moving points, the cubic's vectors A, B, C
/// (f(t) = A(t)·(B(t)×C(t))) and the extent L every tolerance is relative to. VF: A = v − f0, B = f1 − f0,
/// C = f2 − f0.
struct VfMotion {
  Moving v, f0, f1, f2, A, B, C;
  double L = 0;

  /// The query's points in the order of the batched kernels (float_roots.hpp, PointColumns, PointPairing), and
  /// the one the others are taken relative to.
  static QueryPoints points(const VertexFaceQuery& q) {
    return {&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1};
  }
  static constexpr int kOrigin = 1;
  static constexpr PointPairing pairing = PointPairing::vertex_face;

  static VfMotion of(const VertexFaceQuery& q) {
    VfMotion m;
    const QueryPoints p = points(q);
    m.L = extent(p);
    m.v = moving(p, 0, *p[kOrigin]), m.f0 = moving(p, 1, *p[kOrigin]), m.f1 = moving(p, 2, *p[kOrigin]), m.f2 = moving(p, 3, *p[kOrigin]);
    m.A = m.v - m.f0, m.B = m.f1 - m.f0, m.C = m.f2 - m.f0;
    return m;
  }
  static void hits_at(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords) {
    vertex_faces_at(columns, stride, n, verdict, coords);
  }
  /// Whether the vertex is within `reach` of the face at t; sets `out` when it is.
  bool hit(double t, double reach, CcdHit& out) const {
    auto c = closest_point_triangle(v.at(t), f0.at(t), f1.at(t), f2.at(t));
    if (c.distance_sq <= reach * reach) out = {true, t, {c.bary[1], c.bary[2]}};
    return out.hit;
  }
  /// Coplanar motion: where the vertex crosses an edge's line.
  void crossings(TimeList& times) const {
    for (double t : {0.0, 1.0}) {
      Vec3 n = plane_normal({v.at(t), f0.at(t), f1.at(t), f2.at(t)});
      crossing_times(v, f0, f1, n, times);
      crossing_times(v, f1, f2, n, times);
      crossing_times(v, f2, f0, n, times);
    }
  }
};

/// EE: A = b0 − a0, B = a1 − a0, C = b1 − b0.
struct EeMotion {
  Moving a0, a1, b0, b1, A, B, C;
  double L = 0;

  static QueryPoints points(const EdgeEdgeQuery& q) {
    return {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1};
  }
  static constexpr int kOrigin = 0;
  static constexpr PointPairing pairing = PointPairing::edge_edge;

  static EeMotion of(const EdgeEdgeQuery& q) {
    EeMotion m;
    const QueryPoints p = points(q);
    m.L = extent(p);
    m.a0 = moving(p, 0, *p[kOrigin]), m.a1 = moving(p, 1, *p[kOrigin]), m.b0 = moving(p, 2, *p[kOrigin]), m.b1 = moving(p, 3, *p[kOrigin]);
    m.A = m.b0 - m.a0, m.B = m.a1 - m.a0, m.C = m.b1 - m.b0;
    return m;
  }
  static void hits_at(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords) {
    edge_edges_at(columns, stride, n, verdict, coords);
  }
  bool hit(double t, double reach, CcdHit& out) const {
    auto c = closest_segment_segment(a0.at(t), a1.at(t), b0.at(t), b1.at(t));
    if (c.distance_sq <= reach * reach) out = {true, t, {c.s, c.t}};
    return out.hit;
  }
  /// Coplanar motion: where an endpoint crosses the other edge's line.
  void crossings(TimeList& times) const {
    for (double t : {0.0, 1.0}) {
      Vec3 n = plane_normal({a0.at(t), a1.at(t), b0.at(t), b1.at(t)});
      crossing_times(a0, b0, b1, n, times);
      crossing_times(a1, b0, b1, n, times);
      crossing_times(b0, a0, a1, n, times);
      crossing_times(b1, a0, a1, n, times);
    }
  }
};

/// The whole test, one query.
template <class Motion>
CcdHit solve(const Motion& m, double thickness) {
  auto f = [&](double t) { return m.A.at(t).dot(m.B.at(t).cross(m.C.at(t))); };
  const double reach = thickness + FloatTester::rel_tolerance * m.L;
  CcdHit out;
  const auto hit = [&](double t) { return m.hit(t, reach, out); };
  bool degenerate = false;
  if (earliest_hit(m.A, m.B, m.C, f, m.L * m.L * m.L, thickness > 0, degenerate, hit) || !degenerate) return out;
  offer_coplanar_times([&](TimeList& times) { m.crossings(times); }, hit);
  return out;
}

/// The block's rows of coplanar motion (FirstRoot::coplanar; rows of the PointColumns `points`, query_of[row]
/// their query in `queries` and `out`): their candidate times from coplanar_times, sorted and each kept once, then
/// offered in that order, as offer_coplanar_times offers them (so the first hit is its), the distance at each
/// round's times checked in SIMD for every row still open. Rows the kernels leave go to the scalar test whole.
template <class Motion, class Query>
void solve_coplanar(const double* points, std::size_t stride, std::span<const std::uint8_t> rows,
                    const std::uint8_t* query_of, std::span<const Query> queries, double thickness, CcdHit* out) {
  constexpr std::size_t kRows = 64, kStride = kRows + 8;
  alignas(64) double columns[PointColumns::count * kStride];
  alignas(64) double times[kCoplanarSlots * kStride];
  std::array<std::uint8_t, kRows> scalar;
  std::array<std::array<double, kCoplanarSlots>, kRows> sorted;  // each row's times, increasing, each once
  std::array<std::uint8_t, kRows> count, next;                   // how many; the next one to offer
  std::array<AtTime, kRows> verdict;
  std::array<double, 2 * kRows> coords;
  const std::size_t n = rows.size();
  for (int column = 0; column < PointColumns::count; ++column) {
    double* c = columns + kStride * std::size_t(column);
    const double* from = points + stride * std::size_t(column);
    for (std::size_t j = 0; j < n; ++j) c[j] = from[rows[j]];
    std::fill(c + n, c + kStride, 0.0);
  }
  coplanar_times(columns, kStride, n, Motion::pairing, times, scalar.data());
  const auto answer = [&](std::size_t j) -> CcdHit& { return out[query_of[rows[j]]]; };
  std::size_t open = 0;
  for (std::size_t j = 0; j < n; ++j) {
    count[j] = next[j] = 0;
    if (scalar[j]) {
      answer(j) = solve(Motion::of(queries[query_of[rows[j]]]), thickness);
      continue;
    }
    double* list = sorted[j].data();
    std::size_t k = 0;
    for (int slot = 0; slot < kCoplanarSlots; ++slot)
      if (const double t = times[kStride * std::size_t(slot) + j]; t <= 1.0) list[k++] = t;
    std::sort(list, list + k);
    count[j] = std::uint8_t(std::unique(list, list + k) - list);
    ++open;
  }
  double* t_column = columns + kStride * std::size_t(PointColumns::t);
  while (open > 0) {
    for (std::size_t j = 0; j < n; ++j)
      if (next[j] < count[j]) t_column[j] = sorted[j][next[j]];
    Motion::hits_at(columns, kStride, n, verdict.data(), coords.data());
    for (std::size_t j = 0; j < n; ++j) {
      if (next[j] == count[j]) continue;
      const double t = sorted[j][next[j]++];
      if (verdict[j] == AtTime::miss) {
        if (next[j] == count[j]) --open;  // every time missed: no contact
        continue;
      }
      next[j] = count[j], --open;
      if (verdict[j] == AtTime::hit) answer(j) = {true, t, {coords[2 * j], coords[2 * j + 1]}};
      else answer(j) = solve(Motion::of(queries[query_of[rows[j]]]), thickness);
    }
  }
}

/// Many queries: the root search of a block in SIMD (float_roots.hpp), then the distance at the root it found, in
/// SIMD too (`Motion::hit` for the rows that kernel leaves), coplanar motions by their crossing times
/// (solve_coplanar), the candidates after a miss by further passes of the root search (each row asking for its
/// next one), and the whole scalar test where the kernels cannot decide. The same answers as `solve`, bit for
/// bit: the kernels' columns hold what `Motion::of` computes (the points relative to the origin, then A, B, C
/// from them, L), and every candidate is tried in `solve`'s order.
/// With thickness the ends of the step are candidates too, t = 0 before every other and t = 1 after: the distance
/// at t = 0 is checked first, in SIMD, and only the rows it leaves go on to the root search (compacted); a row
/// whose root search ends without a hit has its distance at t = 1 checked last.
template <class Motion, class Query>
void solve_batch(std::span<const Query> queries, double thickness, CcdHit* out) {
  constexpr std::size_t kBlock = 64, kStride = kBlock + 8;  // + 8: whole vectors past a short block's end
  const bool thick = thickness > 0;
  alignas(64) double points[PointColumns::count * kStride];
  alignas(64) double cubic[CubicColumns::count * kStride];
  std::array<FirstRoot, kBlock> kind;
  std::array<double, kBlock> root;
  std::array<std::uint8_t, kBlock> more;
  std::array<AtTime, kBlock> at_root;
  std::array<double, 2 * kBlock> coords;
  std::array<std::uint8_t, kBlock> query_of;  // row of the (compacted) columns → query of the block
  std::array<std::uint8_t, kBlock> at_end_rows;  // rows whose answer is the distance at t = 1 (with thickness)
  std::array<std::uint8_t, kBlock> coplanar_rows;  // rows whose motion is coplanar
  std::array<std::uint8_t, kBlock> again_rows;  // rows whose candidate missed with later ones behind it
  const auto set_time = [&](double t) { std::fill_n(points + kStride * PointColumns::t, kStride, t); };
  for (std::size_t b = 0; b < queries.size(); b += kBlock) {
    const std::size_t n = std::min(kBlock, queries.size() - b);
    std::fill_n(out + b, n, CcdHit{});
    for (std::size_t i = 0; i < n; ++i) {
      const QueryPoints p = Motion::points(queries[b + i]);
      const Vec3& origin = *p[Motion::kOrigin];
      const auto put = [&](int column, const Vec3& v) {
        for (int axis = 0; axis < 3; ++axis) points[kStride * std::size_t(column + axis) + i] = v[axis];
      };
      for (int k = 0; k < 4; ++k) put(PointColumns::P0x + 6 * k, *p[k] - origin), put(PointColumns::dP0x + 6 * k, *p[k + 4] - *p[k]);
      const double L = extent(p);
      points[kStride * PointColumns::extent + i] = L;
      points[kStride * PointColumns::reach + i] = thickness + FloatTester::rel_tolerance * L;
      query_of[i] = std::uint8_t(i);
    }
    for (int column = 0; column < PointColumns::count; ++column)
      std::fill(points + kStride * std::size_t(column) + n, points + kStride * std::size_t(column + 1), 0.0);
    std::size_t rows = n;
    if (thick) {  // t = 0: the hits are answered, the misses compacted into the first rows
      set_time(0.0);
      Motion::hits_at(points, kStride, n, at_root.data(), coords.data());
      rows = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (at_root[i] == AtTime::hit) out[b + i] = {true, 0.0, {coords[2 * i], coords[2 * i + 1]}};
        else if (at_root[i] == AtTime::scalar) out[b + i] = solve(Motion::of(queries[b + i]), thickness);
        else query_of[rows++] = std::uint8_t(i);
      }
      if (rows < n)
        for (int column = 0; column < PointColumns::count; ++column) {
          double* c = points + kStride * std::size_t(column);
          for (std::size_t r = 0; r < rows; ++r) c[r] = c[query_of[r]];
          std::fill(c + rows, c + kStride, 0.0);
        }
      if (rows == 0) continue;
    }
    // The root search, one candidate a row per pass: a row whose candidate missed with later ones behind it
    // (`more`) asks for the next in the following pass, compacted with the others that do.
    std::array<std::uint8_t, kBlock> skip{};  // per row: the candidates it has tried
    for (;;) {
      cubic_columns(points, kStride, rows, Motion::pairing, cubic);
      first_coplanar_roots(cubic, kStride, rows, FloatTester::rel_tolerance, kind.data(), root.data(), more.data(), skip.data());
      std::copy_n(root.data(), rows, points + kStride * PointColumns::t);
      Motion::hits_at(points, kStride, rows, at_root.data(), coords.data());
      std::size_t at_end = 0, coplanar = 0, again = 0;
      for (std::size_t r = 0; r < rows; ++r) {
        const std::size_t i = query_of[r];
        CcdHit& h = out[b + i];
        if (kind[r] == FirstRoot::coplanar) {
          coplanar_rows[coplanar++] = std::uint8_t(r);
          continue;
        }
        const bool miss = kind[r] == FirstRoot::root && at_root[r] == AtTime::miss;
        if (miss && more[r]) {
          again_rows[again++] = std::uint8_t(r);
          continue;
        }
        // The kernel's candidates are spent without a hit: with thickness t = 1 is left, without it nothing.
        if (kind[r] == FirstRoot::none || miss) {
          if (thick) at_end_rows[at_end++] = std::uint8_t(r);
          continue;
        }
        if (kind[r] == FirstRoot::root && at_root[r] == AtTime::hit) {
          h = {true, root[r], {coords[2 * r], coords[2 * r + 1]}};
          continue;
        }
        // What the kernels leave: the distance at the candidate, the whole test.
        const Motion m = Motion::of(queries[b + i]);
        if (!thick && kind[r] == FirstRoot::root && at_root[r] == AtTime::scalar &&
            m.hit(root[r], thickness + FloatTester::rel_tolerance * m.L, h))
          continue;
        if (thick || kind[r] == FirstRoot::scalar || more[r]) h = solve(m, thickness);
      }
      if (coplanar > 0)
        solve_coplanar<Motion>(points, kStride, {coplanar_rows.data(), coplanar}, query_of.data(), queries.subspan(b),
                               thickness, out + b);
      if (at_end > 0) {
        set_time(1.0);
        Motion::hits_at(points, kStride, rows, at_root.data(), coords.data());
        for (std::size_t e = 0; e < at_end; ++e) {
          const std::size_t r = at_end_rows[e], i = query_of[r];
          if (at_root[r] == AtTime::hit) out[b + i] = {true, 1.0, {coords[2 * r], coords[2 * r + 1]}};
          else if (at_root[r] == AtTime::scalar) out[b + i] = solve(Motion::of(queries[b + i]), thickness);
        }
      }
      if (again == 0) break;
      // Compacted in place (again_rows increases, so a row moves only down).
      for (int column = 0; column < PointColumns::count; ++column) {
        double* c = points + kStride * std::size_t(column);
        for (std::size_t k = 0; k < again; ++k) c[k] = c[again_rows[k]];
        std::fill(c + again, c + kStride, 0.0);
      }
      for (std::size_t k = 0; k < again; ++k)
        query_of[k] = query_of[again_rows[k]], skip[k] = std::uint8_t(skip[again_rows[k]] + 1);
      rows = again;
    }
  }
}

}  // namespace

CcdHit FloatTester::vertex_face(const VertexFaceQuery& q) const { return solve(VfMotion::of(q), params_.thickness); }

CcdHit FloatTester::edge_edge(const EdgeEdgeQuery& q) const { return solve(EeMotion::of(q), params_.thickness); }

void FloatTester::vertex_faces(std::span<const VertexFaceQuery> q, CcdHit* out) const {
  solve_batch<VfMotion>(q, params_.thickness, out);
}

void FloatTester::edge_edges(std::span<const EdgeEdgeQuery> q, CcdHit* out) const {
  solve_batch<EeMotion>(q, params_.thickness, out);
}

}  // namespace ccdlab
