#pragma once
// `additive`: additive CCD (Li et al., "Codimensional Incremental Potential Contact", SIGGRAPH 2021, §5), the
// line-search filter of most IPC solvers. Not conservative in floating point; its misses and false hits are
// measured on every shared set (`ccdlab validate`, docs/results-accuracy.md).
//
// The mean displacement of the query's four points is subtracted (distance does not change under a common
// translation); l_p bounds how fast the features can approach: the largest displacement on one side plus the
// largest on the other. From t = 0 the pair is advanced by steps that cannot close the gap g(t) = d(t) − ξ in
// exact arithmetic, Δt = η·g(t)/l_p (the first: η·g(0)/l_p), d the features' distance, ξ the minimum
// separation (`thickness`). The search stops once a step would bring the gap below (1 − η) of its start: the
// pair is reported colliding at the time before that step, a time by which they have not come within ξ. Past
// t = 1 it is not colliding.
//
// So a hit means "this pair limits a step to less than its whole length", not a contact: pairs that approach
// to within (1 − η) of their start gap are hits (false hits against the exact tester), and the time is early
// by design (a line search takes it as a safe step). Distances computed in double and the steps' rounding make
// misses possible, though rare. `max_iterations` bounds the steps: beyond it the pair is reported colliding at
// the time reached (route `fallback`).
#include "framework/primitive/tester.hpp"

namespace ccdlab {

class AdditiveTester final : public PrimitiveTester {
 public:
  struct Params {
    double eta = 0.9;             ///< fraction of the gap a step may close (C-IPC's 1 − s), in (0, 1)
    double thickness = 0;         ///< minimum separation ξ ≥ 0, scene units
    int max_iterations = 10000;   ///< steps per query before the fallback
  };
  AdditiveTester() = default;
  explicit AdditiveTester(Params p);
  [[nodiscard]] std::string_view name() const override { return "additive"; }
  [[nodiscard]] double thickness() const override { return params_.thickness; }
  [[nodiscard]] CcdHit vertex_face(const VertexFaceQuery& q) const override;
  [[nodiscard]] CcdHit edge_edge(const EdgeEdgeQuery& q) const override;

 private:
  Params params_{};
};

}  // namespace ccdlab
