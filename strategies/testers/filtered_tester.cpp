#include "strategies/testers/filtered_tester.hpp"

#include "strategies/testers/interval_ccd.hpp"

namespace ccdlab {
namespace {

template <class Query>
bool certainly_separated(const Query& q) {
  return interval_ccd::certainly_never_coplanar(q) ||
         interval_ccd::classify(interval_ccd::relative_motion(q), 0.0, 1.0) == interval_ccd::Verdict::separated;
}

CcdHit culled() {
  CcdHit h;
  h.route = TestRoute::filter;
  return h;
}

}  // namespace

CcdHit FilteredTester::vertex_face(const VertexFaceQuery& q) const {
  return certainly_separated(q) ? culled() : float_.vertex_face(q);
}

CcdHit FilteredTester::edge_edge(const EdgeEdgeQuery& q) const {
  return certainly_separated(q) ? culled() : float_.edge_edge(q);
}

}  // namespace ccdlab
