#include "strategies/testers/exact_tester.hpp"

#include <optional>

// CGAL's algebraic kernel on GMP integers. This is the only translation unit that includes it (it is heavy
// to compile and is built with -frounding-math, see CMakeLists.txt).
#include <CGAL/Algebraic_kernel_d_1.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "strategies/testers/gmp_block_pool.hpp"
#include "strategies/testers/interval_ccd.hpp"

namespace ccdlab {
namespace {

using Z = CGAL::Gmpz;
using Q = CGAL::Gmpq;
using AK = CGAL::Algebraic_kernel_d_1<Z>;
using Poly = AK::Polynomial_1;
using Root = AK::Algebraic_real_1;
using PVec = std::array<Poly, 3>;

// CGAL's algebraic numbers share reference-counted representations and caches; one query at a time.
std::mutex& kernel_mutex() {
  static std::mutex m;
  return m;
}

PVec operator-(const PVec& a, const PVec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
PVec cross(const PVec& a, const PVec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Poly dot(const PVec& a, const PVec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// Four points moving linearly, x(t) = x0 + t·(x1 − x0), as integer polynomials: every coordinate is scaled
/// by the same power of two 2^−E, where 2^E is the smallest unit among the 24 input doubles.
std::array<PVec, 4> exact_points(const std::array<Vec3, 4>& x0, const std::array<Vec3, 4>& x1) {
  int unit = std::numeric_limits<int>::max();
  auto split = [](double x, long long& mant, int& expo) {  // x = mant · 2^expo, |mant| < 2^53
    int e = 0;
    const double m = std::frexp(x, &e);
    mant = static_cast<long long>(std::ldexp(m, 53));
    expo = e - 53;
  };
  for (const auto* xs : {&x0, &x1})
    for (const Vec3& p : *xs)
      for (int i = 0; i < 3; ++i)
        if (p[i] != 0) {
          long long m = 0;
          int e = 0;
          split(p[i], m, e);
          unit = std::min(unit, e);
        }
  auto to_int = [&](double x) {
    if (x == 0) return Z(0);
    long long m = 0;
    int e = 0;
    split(x, m, e);
    Z z(static_cast<long>(m));
    mpz_mul_2exp(z.mpz(), z.mpz(), static_cast<mp_bitcnt_t>(e - unit));
    return z;
  };
  std::array<PVec, 4> out;
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) {
      const Z a = to_int(x0[k][i]), b = to_int(x1[k][i]);
      out[k][i] = Poly(a, b - a);
    }
  return out;
}

/// Exact signs of polynomials at one algebraic time t. CGAL's sign_at computes a gcd with t's defining
/// polynomial on every call (to recognise a zero); most signs asked here are not zero, and p evaluated in
/// interval arithmetic over a narrow enclosure of t proves them without it. Only a possible zero (the interval
/// holds 0: a contact on a feature's boundary, a point on a line) goes to the gcd. The answers are sign_at's.
class AtTime {
 public:
  AtTime(const AK& ak, const Root& t) : ak_(ak), t_(t) {}
  [[nodiscard]] int sign(const Poly& p) const {
    if (CGAL::is_zero(p)) return 0;
    if (const int s = interval_sign(p); s != 0) return s;
    return int(ak_.sign_at_1_object()(p, t_));
  }
  [[nodiscard]] bool is_zero(const PVec& v) const { return sign(v[0]) == 0 && sign(v[1]) == 0 && sign(v[2]) == 0; }

 private:
  using I = CGAL::Interval_nt<>;  // rounds outward on every operation

  /// The sign of p over an enclosure of t (Horner in intervals), 0 where the interval holds zero. The
  /// enclosure is t narrowed to 2⁻⁶⁰ the first time it is needed (a contact's reported time narrows it to 2⁻⁶⁴).
  [[nodiscard]] int interval_sign(const Poly& p) const {
    if (!enclosure_) {
      const auto [lo, hi] = ak_.approximate_absolute_1_object()(t_, 60);
      enclosure_ = I(CGAL::to_interval(lo).first, CGAL::to_interval(hi).second);
    }
    I v(0);
    for (int i = p.degree(); i >= 0; --i) v = v * *enclosure_ + I(CGAL::to_interval(p[i]));
    return v.inf() > 0 ? 1 : v.sup() < 0 ? -1 : 0;
  }

  const AK& ak_;
  const Root& t_;
  mutable std::optional<I> enclosure_;
};

/// p on the closed segment [a, b] (a = b allowed).
bool on_segment(const AtTime& at, const PVec& p, const PVec& a, const PVec& b) {
  const PVec ap = a - p, bp = b - p;
  return at.is_zero(cross(ap, bp)) && at.sign(dot(ap, bp)) <= 0;
}

/// v in the closed triangle (f0, f1, f2), the four points being coplanar at this time.
bool vertex_in_face(const AtTime& at, const std::array<PVec, 4>& x) {
  const PVec &v = x[0], &f0 = x[1], &f1 = x[2], &f2 = x[3];
  const PVec n = cross(f1 - f0, f2 - f0);
  if (!at.is_zero(n)) {
    // Each sub-triangle (v, fi, fj) must be oriented like the face (or be flat).
    return at.sign(dot(n, cross(f0 - v, f1 - v))) >= 0 && at.sign(dot(n, cross(f1 - v, f2 - v))) >= 0 &&
           at.sign(dot(n, cross(f2 - v, f0 - v))) >= 0;
  }
  // Zero-area face: the union of its three (possibly zero-length) edges.
  return on_segment(at, v, f0, f1) || on_segment(at, v, f1, f2) || on_segment(at, v, f2, f0);
}

/// Closed segments [a0, a1] and [b0, b1] intersect, the four points being coplanar at this time.
bool edges_cross(const AtTime& at, const std::array<PVec, 4>& x) {
  const PVec &a0 = x[0], &a1 = x[1], &b0 = x[2], &b1 = x[3];
  const PVec da = a1 - a0, db = b1 - b0, n = cross(da, db);
  if (!at.is_zero(n)) {  // not parallel: each segment's ends on both sides of (or on) the other's line
    const int s0 = at.sign(dot(n, cross(da, b0 - a0))), s1 = at.sign(dot(n, cross(da, b1 - a0)));
    if (s0 * s1 > 0) return false;
    const int r0 = at.sign(dot(n, cross(db, a0 - b0))), r1 = at.sign(dot(n, cross(db, a1 - b0)));
    return r0 * r1 <= 0;
  }
  // Parallel, collinear or degenerate: they meet iff an end point of one lies on the other.
  return on_segment(at, a0, b0, b1) || on_segment(at, a1, b0, b1) || on_segment(at, b0, a0, a1) ||
         on_segment(at, b1, a0, a1);
}

/// Real roots of p in [0, 1], appended to `out` (p ≢ 0).
void roots_in_step(const AK& ak, const Poly& p, std::vector<Root>& out) {
  std::vector<std::pair<Root, AK::Multiplicity_type>> roots;
  ak.solve_1_object()(p, Q(0), Q(1), std::back_inserter(roots));
  for (auto& r : roots) out.push_back(r.first);
}

/// Whether p (degree ≤ 2) certainly has no zero in [0, 1]: its Bernstein coefficients there, times 2 — 2c₀,
/// 2c₀ + c₁, 2(c₀ + c₁ + c₂) — all of one strict sign (p is their convex combination). Exact, in integers.
bool never_zero_in_step(const Poly& p) {
  if (CGAL::is_zero(p) || p.degree() > 2) return false;
  const auto coeff = [&](int i) { return i <= p.degree() ? p[i] : Z(0); };
  const Z b0 = 2 * coeff(0), b1 = b0 + coeff(1), b2 = 2 * (coeff(0) + coeff(1) + coeff(2));
  const int s = CGAL::sign(b0);
  return s != 0 && CGAL::sign(b1) == s && CGAL::sign(b2) == s;
}

/// A rational time num/den, den > 0.
struct Rational {
  Z num, den;
};

/// The root of a polynomial of degree 1.
Rational root_of_linear(const Poly& g) { return g[1] > 0 ? Rational{-g[0], g[1]} : Rational{g[0], -g[1]}; }

/// p(r)·denⁿ (n = deg p), by Horner in integers: zero exactly where p(r) is.
Z scaled_value(const Poly& p, const Rational& r) {
  Z value = p[p.degree()], den_power = r.den;
  for (int i = p.degree() - 1; i >= 0; --i, den_power *= r.den) value = value * r.num + p[i] * den_power;
  return value;
}

/// q = c·p for a rational c (same degree, coefficient ratios equal).
bool proportional(const Poly& p, const Poly& q) {
  const int d = p.degree();
  if (q.degree() != d) return false;
  for (int i = 0; i < d; ++i)
    if (p[i] * q[d] != q[i] * p[d]) return false;
  return true;
}

/// The times in [0, 1] where all three coordinates of v vanish (v ≢ 0; coordinates of degree ≤ 2, as every
/// event's are: differences of moving points are linear, their cross products quadratic), appended to `out`. No
/// time where only one coordinate vanishes is kept (it cannot change the predicate). Decided in integers, with
/// at most one root isolation: take the lowest-degree coordinate p. Another coordinate q either is a multiple of
/// p (it shares all of p's roots) or shares at most one root with it, a rational one — the root of p itself when
/// p is linear, else of q₂·p − p₂·q (degree ≤ 1). So the common zeros are all of p's roots, when every coordinate
/// is a multiple of p, or one rational time, checked exactly in each coordinate.
void common_zeros(const AK& ak, const PVec& v, std::vector<Root>& out) {
  if (std::any_of(v.begin(), v.end(), never_zero_in_step)) return;
  const Poly* lowest = nullptr;
  for (const Poly& c : v)
    if (!CGAL::is_zero(c) && (lowest == nullptr || c.degree() < lowest->degree())) lowest = &c;
  if (lowest == nullptr || lowest->degree() == 0) return;  // zero throughout, or never zero: no event time
  CGAL_precondition(std::all_of(v.begin(), v.end(), [](const Poly& c) { return c.degree() <= 2; }));
  std::optional<Rational> only;  // the one time the coordinates so far share, unless they share all of p's roots
  if (lowest->degree() == 1) only = root_of_linear(*lowest);
  for (const Poly& q : v) {
    if (&q == lowest || CGAL::is_zero(q)) continue;
    if (!only) {  // p is quadratic, so is q
      if (proportional(*lowest, q)) continue;
      const Poly g = q[2] * *lowest - (*lowest)[2] * q;
      if (g.degree() == 0) return;  // a nonzero constant: no common root
      only = root_of_linear(g);
      if (!CGAL::is_zero(scaled_value(*lowest, *only))) return;
    }
    if (!CGAL::is_zero(scaled_value(q, *only))) return;
  }
  if (!only) return roots_in_step(ak, *lowest, out);
  if (!CGAL::is_negative(only->num) && only->num <= only->den)
    out.push_back(ak.construct_algebraic_real_1_object()(Q(only->num, only->den)));
}

ExactTester::Decision decide_points(const std::array<Vec3, 4>& x0, const std::array<Vec3, 4>& x1, bool edge_edge) {
  const std::array<PVec, 4> x = exact_points(x0, x1);
  // The coplanarity cubic f(t) = A·(B×C), with A, B, C as in interval_ccd.hpp.
  const Poly f = edge_edge ? dot(x[2] - x[0], cross(x[1] - x[0], x[3] - x[2]))
                           : dot(x[0] - x[1], cross(x[2] - x[1], x[3] - x[1]));

  std::lock_guard lock(kernel_mutex());
  AK ak;
  if (CGAL::is_zero(f.evaluate(Z(0)))) {
    // Coplanar at the start (a contact the last step ended in, most often): when the features meet there, 0 is
    // the earliest contact and no root needs isolating (the queries certification leaves to the algebra are
    // mostly these).
    const Root start = ak.construct_algebraic_real_1_object()(Z(0));
    const AtTime at(ak, start);
    if (edge_edge ? edges_cross(at, x) : vertex_in_face(at, x)) return {true, 0.0, 0.0, false};
  }
  std::vector<Root> times;
  if (!CGAL::is_zero(f)) {
    roots_in_step(ak, f, times);
  } else {
    // Coplanar throughout: the events where a pair of points coincides or a triple becomes collinear.
    times.push_back(ak.construct_algebraic_real_1_object()(Z(0)));
    times.push_back(ak.construct_algebraic_real_1_object()(Z(1)));
    std::vector<PVec> events;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) events.push_back(x[j] - x[i]);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        for (int k = j + 1; k < 4; ++k) events.push_back(cross(x[j] - x[i], x[k] - x[i]));
    if (edge_edge) events.push_back(cross(x[1] - x[0], x[3] - x[2]));
    for (const PVec& e : events) common_zeros(ak, e, times);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
  }
  for (const Root& t : times) {
    const AtTime at(ak, t);
    if (edge_edge ? edges_cross(at, x) : vertex_in_face(at, x)) {
      const auto bounds = ak.approximate_absolute_1_object()(t, 64);  // |hi − lo| ≤ 2^−64
      return {true, CGAL::to_interval(bounds.first).first, CGAL::to_interval(bounds.second).second, false};
    }
  }
  return {};
}

// The decision of the interval classification of f's windows, when it reaches one (see the header); a contact
// window is narrowed by interval_ccd::narrow_root.

/// What settling one window led to: none of its contacts (go on to the next), the earliest contact (`out`), or
/// nothing proven (the algebra decides the query).
enum class Settled { apart, contact, undecided };

/// Settles [a, b], a window where f may vanish with none of the query's contacts before a. A window classified
/// `unknown` is halved, earliest half first, at most `depth` times: a window is often unknown only because the
/// features cross each other's boundary somewhere in it, away from f's root, and a narrower window around the
/// root is proven (what spares most queries the algebra). `budget` caps the classifications a query
/// spends.
Settled settle(const interval_ccd::RelativeMotion& m, double a, double b, int depth, int& budget,
               std::optional<ExactTester::Decision>& out) {
  constexpr double kToiWidth = 0x1p-30;
  if (--budget < 0) return Settled::undecided;
  switch (interval_ccd::classify(m, a, b)) {
    case interval_ccd::Verdict::separated:
      return Settled::apart;
    case interval_ccd::Verdict::contact: {
      const auto [lo, hi] = interval_ccd::narrow_root(m, a, b);
      if (hi - lo > kToiWidth) return Settled::undecided;  // the time stays too loose: the algebra gives it to adjacent doubles
      out = ExactTester::Decision{true, lo, hi, true};
      return Settled::contact;
    }
    case interval_ccd::Verdict::unknown:
      break;
  }
  const double mid = 0.5 * (a + b);
  if (depth == 0 || !(mid > a && mid < b)) return Settled::undecided;
  const Settled left = settle(m, a, mid, depth - 1, budget, out);
  return left == Settled::apart ? settle(m, mid, b, depth - 1, budget, out) : left;
}

std::optional<ExactTester::Decision> certified(const interval_ccd::RelativeMotion& m) {
  constexpr double kWindowWidth = 0x1p-12;
  constexpr int kMaxWindows = 64;   // more: f near zero over much of the step (coplanar motion)
  constexpr int kMaxHalvings = 12;  // an unknown window of 2⁻¹² down to 2⁻²⁴
  int budget = 96;                  // classifications, all windows together
  std::optional<ExactTester::Decision> out;
  bool undecided = false;
  int windows = 0;
  interval_ccd::for_each_coplanarity_window(m, 0.0, 1.0, kWindowWidth, [&](double a, double b) {
    if (++windows > kMaxWindows) return undecided = true;
    const Settled s = settle(m, a, b, kMaxHalvings, budget, out);
    if (s == Settled::undecided) undecided = true;
    return s != Settled::apart;
  });
  if (!out && !undecided) out = ExactTester::Decision{false, 1, 1, true};
  return undecided ? std::nullopt : out;
}

template <class Query>
std::optional<ExactTester::Decision> without_algebra(const Query& q, const ExactTester::Params& p) {
  if (p.prefilter && interval_ccd::certainly_never_coplanar(q)) return ExactTester::Decision{false, 1, 1, true};
  if (!p.prefilter && !p.certify) return std::nullopt;
  const interval_ccd::RelativeMotion m = interval_ccd::relative_motion(q);
  if (p.prefilter && interval_ccd::classify(m, 0, 1) == interval_ccd::Verdict::separated)
    return ExactTester::Decision{false, 1, 1, true};
  return p.certify ? certified(m) : std::nullopt;
}

}  // namespace

ExactTester::ExactTester(Params p) : params_(p) { recycle_gmp_blocks(); }

ExactTester::Decision ExactTester::decide(const VertexFaceQuery& q) const {
  if (const auto d = without_algebra(q, params_)) return *d;
  return decide_points({q.v_t0, q.f0_t0, q.f1_t0, q.f2_t0}, {q.v_t1, q.f0_t1, q.f1_t1, q.f2_t1}, false);
}

ExactTester::Decision ExactTester::decide(const EdgeEdgeQuery& q) const {
  if (const auto d = without_algebra(q, params_)) return *d;
  return decide_points({q.ea0_t0, q.ea1_t0, q.eb0_t0, q.eb1_t0}, {q.ea0_t1, q.ea1_t1, q.eb0_t1, q.eb1_t1}, true);
}

namespace {

template <class Query>
CcdHit as_hit(const ExactTester::Decision& d, const Query& q) {
  CcdHit h;
  h.route = d.prefiltered ? TestRoute::filter : TestRoute::main;
  if (!d.hit) return h;
  h.hit = true;
  h.toi = d.toi_lo;
  h.coords = contact_coords(q, d.toi_lo);
  return h;
}

}  // namespace

CcdHit ExactTester::vertex_face(const VertexFaceQuery& q) const { return as_hit(decide(q), q); }
CcdHit ExactTester::edge_edge(const EdgeEdgeQuery& q) const { return as_hit(decide(q), q); }

std::vector<ToiReference> exact_reference(const QuerySet& set) {
  const ExactTester exact;
  std::vector<ToiReference> reference(set.size());
  for (std::size_t i = 0; i < set.size(); ++i) {
    const auto d = set.kind == ContactKind::vf ? exact.decide(set.vf[i]) : exact.decide(set.ee[i]);
    reference[i] = {d.hit, d.toi_lo, d.toi_hi};
  }
  return reference;
}

}  // namespace ccdlab
