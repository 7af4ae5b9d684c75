#include "strategies/testers/filtered_tester.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

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

/// The queries the filter cannot settle, handed to `float` together; the rest are culled.
template <class Query, class Batch>
void filter_then(std::span<const Query> queries, CcdHit* out, Batch&& batch) {
  constexpr std::size_t kBlock = 64;
  std::array<Query, kBlock> left;
  std::array<std::uint32_t, kBlock> where;
  std::array<CcdHit, kBlock> hits;
  for (std::size_t b = 0; b < queries.size(); b += kBlock) {
    const std::size_t n = std::min(kBlock, queries.size() - b);
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (certainly_separated(queries[b + i])) {
        out[b + i] = culled();
      } else {
        left[m] = queries[b + i], where[m++] = std::uint32_t(b + i);
      }
    }
    batch(std::span<const Query>(left.data(), m), hits.data());
    for (std::size_t j = 0; j < m; ++j) out[where[j]] = hits[j];
  }
}

}  // namespace

void FilteredTester::vertex_faces(std::span<const VertexFaceQuery> q, CcdHit* out) const {
  filter_then(q, out, [&](std::span<const VertexFaceQuery> left, CcdHit* hits) { float_.vertex_faces(left, hits); });
}

void FilteredTester::edge_edges(std::span<const EdgeEdgeQuery> q, CcdHit* out) const {
  filter_then(q, out, [&](std::span<const EdgeEdgeQuery> left, CcdHit* hits) { float_.edge_edges(left, hits); });
}

CcdHit FilteredTester::vertex_face(const VertexFaceQuery& q) const {
  return certainly_separated(q) ? culled() : float_.vertex_face(q);
}

CcdHit FilteredTester::edge_edge(const EdgeEdgeQuery& q) const {
  return certainly_separated(q) ? culled() : float_.edge_edge(q);
}

}  // namespace ccdlab
