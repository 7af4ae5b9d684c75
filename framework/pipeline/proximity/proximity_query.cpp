#include "framework/pipeline/proximity/proximity_query.hpp"

#include <string_view>
#include <utility>

#include "framework/util/error.hpp"
#include "framework/util/parallel.hpp"

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
  // Each hit described (its distance and closest features), on the query's threads.
  const Contacts& hits = r.step.contacts;
  r.pairs.resize(hits.size());
  PhaseTrace trace;
  parallel_chunks(hits.size(), 4096, pipeline_.strategies().threads, trace, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t i = b; i < e; ++i) r.pairs[i] = describe_proximity(hits[i], x);
  });
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
