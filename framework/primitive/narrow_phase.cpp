#include "framework/primitive/narrow_phase.hpp"

namespace ccdlab {
namespace {

void count_route(const CcdHit& hit, StepCounters& c) {
  c.tests_filtered += hit.route == TestRoute::filter;
  c.tests_fallback += hit.route == TestRoute::fallback;
}

}  // namespace

void NarrowPhase::begin_step(const Positions& x_t0, const Positions& x_t1, int threads, PhaseTrace* trace) {
  x_t0_ = &x_t0;
  x_t1_ = &x_t1;
  const double eta = tester_.thickness();
  vertex_box_.resize(x_t0.size());
  edge_box_.resize(mesh_.num_edges());
  face_box_.resize(mesh_.num_faces());
  PhaseTrace unused, part;
  PhaseTrace& out = trace ? *trace : unused;
  constexpr std::size_t chunk = 4096;
  parallel_chunks(x_t0.size(), chunk, threads, out, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t v = b; v < e; ++v) {
      vertex_box_[v].lo = x_t0[v].cwiseMin(x_t1[v]);
      vertex_box_[v].hi = x_t0[v].cwiseMax(x_t1[v]);
    }
  });
  // Edge and face boxes need every vertex box: a second and third parallel loop, traced as more tasks.
  auto append = [&](const PhaseTrace& p) {
    out.task_ms.insert(out.task_ms.end(), p.task_ms.begin(), p.task_ms.end());
    for (std::size_t t = 0; t < p.thread_ms.size() && t < out.thread_ms.size(); ++t) out.thread_ms[t] += p.thread_ms[t];
  };
  parallel_chunks(std::size_t(mesh_.num_edges()), chunk, threads, part, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t i = b; i < e; ++i) {
      Box3 box = vertex_box_[mesh_.edge(Index(i))[0]];
      box.grow(vertex_box_[mesh_.edge(Index(i))[1]]);
      box.inflate(eta);
      edge_box_[i] = box;
    }
  });
  append(part);
  parallel_chunks(std::size_t(mesh_.num_faces()), chunk, threads, part, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t f = b; f < e; ++f) {
      const Face& t = mesh_.face(Index(f));
      Box3 box = vertex_box_[t[0]];
      box.grow(vertex_box_[t[1]]);
      box.grow(vertex_box_[t[2]]);
      box.inflate(eta);
      face_box_[f] = box;
    }
  });
  append(part);
}

VertexFaceQuery NarrowPhase::vf_query(Index v, Index f) const {
  const Face& t = mesh_.face(f);
  const Positions &x0 = *x_t0_, &x1 = *x_t1_;
  return {x0[v], x0[t[0]], x0[t[1]], x0[t[2]], x1[v], x1[t[0]], x1[t[1]], x1[t[2]]};
}

EdgeEdgeQuery NarrowPhase::ee_query(Index a, Index b) const {
  const Edge &ea = mesh_.edge(a), &eb = mesh_.edge(b);
  const Positions &x0 = *x_t0_, &x1 = *x_t1_;
  return {x0[ea[0]], x0[ea[1]], x0[eb[0]], x0[eb[1]], x1[ea[0]], x1[ea[1]], x1[eb[0]], x1[eb[1]]};
}

void NarrowPhase::test_vf(Index v, Index f, std::vector<Contact>& out, StepCounters& c, bool box_cull) const {
  const Face& t = mesh_.face(f);
  ++c.vf_pairs;
  if (box_cull && !face_box_[f].overlaps(vertex_box_[v])) return;
  ++c.vf_tests;
  CcdHit hit = tester_.vertex_face(vf_query(v, f));
  count_route(hit, c);
  if (!hit.hit) return;
  ++c.contacts_vf;
  out.push_back(Contact{ContactKind::vf, v, f, {v, t[0], t[1], t[2]}, hit.toi, hit.coords});
}

void NarrowPhase::test_ee(Index a, Index b, std::vector<Contact>& out, StepCounters& c, bool box_cull) const {
  if (a > b) std::swap(a, b);
  const Edge &ea = mesh_.edge(a), &eb = mesh_.edge(b);
  ++c.ee_pairs;
  if (box_cull && !edge_box_[a].overlaps(edge_box_[b])) return;  // both inflated: a 2η margin, still conservative
  ++c.ee_tests;
  CcdHit hit = tester_.edge_edge(ee_query(a, b));
  count_route(hit, c);
  if (!hit.hit) return;
  ++c.contacts_ee;
  out.push_back(Contact{ContactKind::ee, a, b, {ea[0], ea[1], eb[0], eb[1]}, hit.toi, hit.coords});
}

void NarrowPhase::test_face_pair(Index fa, Index fb, std::vector<Contact>& out, StepCounters& c,
                                 StepResult* record) const {
  const std::uint8_t ma = owners_.owned_mask[fa], mb = owners_.owned_mask[fb];
  const Face &ta = mesh_.face(fa), &tb = mesh_.face(fb);
  for (int j = 0; j < 3; ++j) {
    if (ma & (1u << j)) {
      test_vf(ta[j], fb, out, c);
      if (record) record->tested_vf.push_back({ta[j], fb});
    }
    if (mb & (1u << j)) {
      test_vf(tb[j], fa, out, c);
      if (record) record->tested_vf.push_back({tb[j], fa});
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (!(ma & (8u << i))) continue;
    for (int j = 0; j < 3; ++j) {
      if (!(mb & (8u << j))) continue;
      Index a = mesh_.face_edges(fa)[i], b = mesh_.face_edges(fb)[j];
      test_ee(a, b, out, c);
      if (record) record->tested_ee.push_back({std::min(a, b), std::max(a, b)});
    }
  }
}

}  // namespace ccdlab
