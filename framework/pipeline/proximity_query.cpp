#include "framework/pipeline/proximity_query.hpp"

#include <string_view>
#include <utility>

#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

PipelineStrategies with_static_distance(PipelineStrategies s, double dhat) {
  s.tester = std::make_unique<StaticDistanceTester>(dhat);
  s.normal_cones = false;
  return s;
}

}  // namespace

ProximityQuery::ProximityQuery(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies, double dhat)
    : dhat_(dhat), pipeline_(mesh, std::move(bodies), with_static_distance(std::move(strategies), dhat)) {}

ProximityResult ProximityQuery::query(const Positions& x) {
  ProximityResult r;
  try {
    r.step = pipeline_.step(x, x);
  } catch (const Error& e) {  // the pipeline's refusals name its step; here it is this query
    const std::string_view m = e.what();
    if (m.starts_with("step: ")) throw Error(fmt::format("proximity query: {}", m.substr(6)));
    throw;
  }
  r.hash = contact_set_hash(r.step.contacts);
  r.pairs.reserve(r.step.contacts.size());
  for (const Contact& c : r.step.contacts) r.pairs.push_back(describe_proximity(c, x));
  r.step.contacts = {};
  return r;
}

ProximityPair describe_proximity(const Contact& hit, const Positions& x) {
  const std::array<Index, 4>& v = hit.vertices;
  const ClosestFeatures f = hit.kind == ContactKind::vf ? closest_vertex_face(x[v[0]], x[v[1]], x[v[2]], x[v[3]])
                                                         : closest_edge_edge(x[v[0]], x[v[1]], x[v[2]], x[v[3]]);
  return {hit.kind, v, f.distance, f.type, f.coords};
}

}  // namespace ccdlab
