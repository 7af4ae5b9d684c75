#pragma once
// `exact`: the reference checker. Decides every elementary query (zero thickness, linear motion over
// t ∈ [0, 1]) exactly, with CGAL's univariate algebraic kernel on GMP integers — no tolerance anywhere.
//
// Inputs are doubles, hence dyadic rationals: scaled by one common power of two they become integers, and
// every quantity below is a polynomial in t with integer coefficients (signs do not change under the scaling).
//  * If the coplanarity cubic f(t) is not identically zero, contact can only happen at its real roots in
//    [0, 1]; each root is isolated exactly and the "point in triangle" / "segments cross" predicate is
//    evaluated there by exact signs of polynomials at an algebraic number (CGAL Sign_at_1).
//  * If f ≡ 0 (the four points stay coplanar: coplanar motion, parallel or collinear edges, zero-area
//    faces, no motion), the set of contact times is closed and the predicate's truth can only change where a
//    pair of points coincides or a triple becomes collinear; so the predicate is evaluated at t = 0, t = 1
//    and at every time one of those events happens (a common root of a difference's or cross product's three
//    coordinates: one rational time or all roots of one coordinate, told apart in integers). The earliest time
//    it holds is the time of contact.
// Signs at an algebraic time are proven by interval evaluation over a 2⁻⁶⁰ enclosure of it where they can be;
// only a possible zero takes CGAL's exact test (a gcd with the time's defining polynomial).
// The predicates handle degenerate faces (a segment or a point) and degenerate edges (a point) explicitly.
// Time of contact: the exact algebraic root, reported as a double interval [toi_lo, toi_hi] enclosing it.
// GMP's blocks come from per-thread lists (gmp_block_pool.hpp), installed when the first tester is constructed.
//
// An interval prefilter (the certified Bernstein bound of interval_ccd.hpp, which proves "no coplanarity
// and no crossing in [0, 1]") answers most non-colliding queries without GMP; it never changes an answer.
// Certification (`certify`) then settles most of the rest, true contacts above all, still without GMP: the
// step is cut into the windows where f may vanish (at most 2⁻¹² wide, earliest first; outside them f ≠ 0,
// proven) and each is classified with interval bounds. Separated windows are skipped; the first window
// classified `contact` (f changes sign there and the features are strictly inside / crossing throughout) holds
// the earliest contact, proven: hit, and bisection narrows the time (halves where f ≠ 0 are dropped, halves with
// a proven contact kept) as far as interval bounds prove; an enclosure left wider than 2⁻³⁰ goes to the algebra
// (whose enclosures are adjacent doubles; certify=false gives those for every hit).
// A window classified `unknown` is halved, earliest half first, down to 2⁻²⁴ (often only the features' crossing
// of each other's boundary elsewhere in the window kept it unknown). When every window is separated: no
// contact, proven. Only a window still `unknown` (a grazing or degenerate contact, or one at t = 0) or coplanar
// motion (too many windows) goes on to the algebra, which first checks t = 0 itself: features that meet there
// (coplanar at the start, the contact the last step ended in) have their earliest contact at 0, with no root
// to isolate.
#include "framework/primitive/tester.hpp"
#include "framework/queries/evaluate.hpp"

namespace ccdlab {

class ExactTester final : public PrimitiveTester {
 public:
  struct Params {
    bool prefilter = true;  ///< decide certainly-separated queries with interval arithmetic first
    bool certify = true;    ///< decide by interval classification of coplanarity windows before any algebra
  };
  /// The exact answer; toi_lo ≤ exact time of contact ≤ toi_hi (both 1 when there is no hit).
  struct Decision {
    bool hit = false;
    double toi_lo = 1.0, toi_hi = 1.0;
    bool prefiltered = false;  ///< decided by the interval prefilter or certification (no GMP)
  };

  /// Installs GMP's block pool (gmp_block_pool.hpp): construct testers before steps run on other threads.
  ExactTester() : ExactTester(Params{}) {}
  explicit ExactTester(Params p);
  [[nodiscard]] std::string_view name() const override { return "exact"; }
  [[nodiscard]] double thickness() const override { return 0.0; }
  [[nodiscard]] CcdHit vertex_face(const VertexFaceQuery& q) const override;
  [[nodiscard]] CcdHit edge_edge(const EdgeEdgeQuery& q) const override;
  /// Exact contact at zero distance: nothing farther than 0 is ever reported.
  [[nodiscard]] std::optional<CullReach> cull_reach() const override { return CullReach{0, 0}; }

  [[nodiscard]] Decision decide(const VertexFaceQuery& q) const;
  [[nodiscard]] Decision decide(const EdgeEdgeQuery& q) const;

 private:
  Params params_{};
};

/// The exact answer to every query of a set (hit, and the interval holding its time of contact): the reference
/// `ccdlab validate` and `ccdlab.validate` score every tester against.
std::vector<ToiReference> exact_reference(const QuerySet& set);

}  // namespace ccdlab
