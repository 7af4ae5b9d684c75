#pragma once
// ProximityQuery: every vertex–face and edge–edge pair closer than d̂ at positions x — the active set of a barrier
// (IPC-style) contact term — with each pair's distance and closest-feature type (docs/proximity.md).
//
// It is the CCD pipeline run on the step x → x with the static distance test as its tester
// (framework/primitive/static_distance.hpp): the same bodies, collision rules and representative ownership (each
// non-adjacent pair tested once), the same k-DOP hierarchies (built once, refit on every query, their volumes
// inflated by d̂ and rounded outward), schedulers, culling stages, memory plan and work estimate (a d̂ larger than
// the scene is refused as a CCD thickness is). With no motion every stage's bound is a bound on the distance at x,
// so the culling drops only pairs proven farther than d̂, and the test decides the rest exactly.
#include <array>
#include <cstdint>
#include <vector>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/primitive/static_distance.hpp"

namespace ccdlab {

/// One pair closer than d̂: vertices as a Contact's (VF: v, f0, f1, f2; EE: ea0, ea1, eb0, eb1), its distance in
/// double, and its closest features (static_distance.hpp).
struct ProximityPair {
  ContactKind kind;
  std::array<Index, 4> vertices;
  double distance;
  DistanceType type;
  std::array<double, 2> coords;  ///< VF: barycentric weights of f1, f2; EE: parameters along edge a, edge b
};

struct ProximityResult {
  std::vector<ProximityPair> pairs;  ///< sorted by feature identity (VF by vertex then face, then EE), as contacts
  std::uint64_t hash = 0;            ///< contact_set_hash of the pairs: the same convention as a CCD step's
  StepResult step;                   ///< the pipeline's counters and timings (its contacts moved into `pairs`)
};

class ProximityQuery {
 public:
  /// `strategies` as for a CCD pipeline; its tester is replaced by the static distance test at `dhat` and normal
  /// cones are turned off (they cull only pairs that would have to cross, not pairs that are merely near).
  /// `mesh` must outlive the query.
  ProximityQuery(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies, double dhat);

  /// The pairs closer than dhat() at positions x (the mesh's vertex count, finite).
  ProximityResult query(const Positions& x);

  [[nodiscard]] double dhat() const { return dhat_; }
  [[nodiscard]] CcdPipeline& pipeline() { return pipeline_; }

 private:
  double dhat_;
  CcdPipeline pipeline_;
};

/// The proximity pair a hit of the static distance test describes, at positions x.
ProximityPair describe_proximity(const Contact& hit, const Positions& x);

}  // namespace ccdlab
