#pragma once
// `conservative`: never misses a collision (linear motion). At thickness η > 0 it reports every pair that comes
// within η, by a search over time and the features' points (separation_search.hpp). What follows is the
// zero-thickness search. Every rounding error is accounted for (forward error bounds and interval arithmetic,
// interval_ccd.hpp). The roots of the coplanarity cubic are isolated first (or, for coplanar motion, the whole
// step is taken at once); those windows are bisected in time and each is classified by certified Bernstein
// bounds:
//   separated → dropped;  contact (proven root of f, features strictly inside) → hit;  unknown → bisected.
// Windows are visited earliest first, so the first hit's window start is a lower bound on the time of
// contact; the time is then narrowed to `toi_tolerance` with the (cheaper) coplanarity test alone.
//
// δ (`delta`) trades false hits for time: a window still unknown once the features move less than δ·L
// within it (L = the query's bounding-box diagonal — δ is relative, so answers do not depend on the scale)
// goes to the fallback: report a hit (never wrong for a collision, possibly a near miss), or ask the `exact`
// tester. Unlike δ-inclusion methods (Tight-Inclusion), only time is bisected and the inside / crossing
// conditions are exact polynomial signs, so near misses farther than ≈δ·L are resolved. Before a `hit`
// fallback is reported, the separation search checks that the features come within 2δ·L at all: a pair proven
// farther all step cannot touch and is a miss. That bounds what is ever reported, the tester's cull reach.
#include "strategies/testers/exact_tester.hpp"
#include "strategies/testers/interval_ccd.hpp"
#include "strategies/testers/separation_search.hpp"

namespace ccdlab {

class ConservativeTester final : public PrimitiveTester {
 public:
  enum class Fallback { hit, exact };
  struct Params {
    double delta = 1e-6;          ///< relative spatial tolerance of an undecided window (≥ 0)
    Fallback fallback = Fallback::hit;
    int max_windows = 512;        ///< bound on windows per query (bounds the tail); beyond it: fallback
    double toi_tolerance = 1e-6;  ///< width of the final time window of a hit
    double thickness = 0;         ///< η ≥ 0: report every pair that comes within η (fallback `hit` only)
    int max_boxes = 4096;         ///< with thickness: boxes of (t, u, v) per query before the fallback
  };
  ConservativeTester() = default;
  explicit ConservativeTester(Params p);
  [[nodiscard]] std::string_view name() const override { return "conservative"; }
  [[nodiscard]] double thickness() const override { return params_.thickness; }
  [[nodiscard]] CcdHit vertex_face(const VertexFaceQuery& q) const override;
  [[nodiscard]] CcdHit edge_edge(const EdgeEdgeQuery& q) const override;
  /// A hit is a certified contact (distance ≤ η), or undecided with the features within η + 4δ·L (a box of the
  /// separation search smaller than δ·L and within 2δ·L at zero thickness, or η at thickness η; its centre is
  /// then within √3·δ·L more). The exception: a query that spends all of `max_boxes` is reported at an unknown
  /// distance — the batched narrow phase may then have dropped, as farther than the reach, a pair the scalar
  /// mode reports; never one that comes within η.
  [[nodiscard]] std::optional<CullReach> cull_reach() const override { return CullReach{params_.thickness, 4 * params_.delta + kReachFloor}; }

  /// Zero thickness: the earliest window of width 2^-32 at or after `toi` where f may vanish (any contact needs
  /// f = 0, and none is earlier than `toi`). With a thickness: `toi` (the search's own `toi_tolerance`).
  [[nodiscard]] double tighten_toi(const VertexFaceQuery& q, double toi) const override;
  [[nodiscard]] double tighten_toi(const EdgeEdgeQuery& q, double toi) const override;

  static Fallback parse_fallback(const std::string& name);

 private:
  template <class Query>
  CcdHit search(const Query& q) const;
  /// The start of the earliest sub-window of [tl, th], toi_tolerance wide, where f may vanish: a lower bound
  /// on any contact time in [tl, th] (all of them need coplanarity).
  [[nodiscard]] double earliest_root(const interval_ccd::RelativeMotion& m, double tl, double th) const;

  template <class Query>
  [[nodiscard]] double tighten(const Query& q, double toi) const;

  [[nodiscard]] separation::Params separation_params() const;
  /// Whether the features may come within 2δ·L during the step (false: proven farther, they cannot touch).
  /// `t_hint`: a time where they may be closest (a witness is tried there before the search).
  template <class Query>
  [[nodiscard]] bool may_come_close(const Query& q, double L, double t_hint) const;
  /// The least relative reach, for δ = 0.
  static constexpr double kReachFloor = 0x1p-40;

  Params params_{};
  ExactTester exact_{};
};

}  // namespace ccdlab
