#include "framework/narrow/representatives.hpp"

#include <algorithm>
#include <tuple>

#include "framework/util/error.hpp"

namespace ccdlab {

Index Representatives::face_of_vertex(Index v) const {
  return rule_ == RepresentativeRule::fixed ? owners_.vertex_owner[v] : mesh_.vertex_faces(v)[0];
}
Index Representatives::face_of_edge(Index e) const {
  return rule_ == RepresentativeRule::fixed ? owners_.edge_owner[e] : mesh_.edge_faces(e)[0];
}

std::size_t Representatives::append_pairs(std::span<const FacePair> candidates, UninitializedVector<VertexFacePair>& vf,
                                          UninitializedVector<EdgeEdgePair>& ee, bool simd, bool carry_orphans) const {
  if (rule_ != RepresentativeRule::fixed) {
    for (const FacePair& p : candidates)
      for_each_pair(
          p.a, p.b, [&](Index v, Index f) { vf.push_back({v, f}); }, [&](Index a, Index b) { ee.push_back({a, b}); });
    return 0;
  }
  append_owned(candidates, vf, ee, simd);
  if (!carry_orphans || carried_.empty()) return 0;
  std::size_t carried = 0;
  const std::uint64_t* bits = carried_bits_.data();
  for (const FacePair& p : candidates) {
    const std::uint64_t want_a = carried_bits(p.b), want_b = carried_bits(p.a);
    if ((bits[p.a] & want_a) == want_a) carried += append_carried(p.a, p.b, vf, ee);
    if ((bits[p.b] & want_b) == want_b) carried += append_carried(p.b, p.a, vf, ee);
  }
  return carried;
}

std::size_t Representatives::append_carried(Index carrier, Index other, UninitializedVector<VertexFacePair>& vf,
                                            UninitializedVector<EdgeEdgePair>& ee) const {
  std::size_t n = 0;
  for (std::uint32_t k = carried_start_[std::size_t(carrier)], end = carried_start_[std::size_t(carrier) + 1]; k < end; ++k) {
    const CarriedOrphan& o = carried_[k];
    if (o.other != other) continue;
    if (o.b < 0) vf.push_back({o.a, other});
    else ee.push_back({o.a, o.b});
    ++n;
  }
  return n;
}

void Representatives::build_carried_orphans() {
  // Counting sort by carrier: carried_start_ holds each face's count, then its list's start.
  std::vector<Index> carrier_of_vf(orphans_.vf.size(), -1), carrier_of_ee(orphans_.ee.size(), -1);
  std::vector<Index> other_of_ee(orphans_.ee.size(), -1);
  carried_start_.assign(std::size_t(mesh_.num_faces()) + 1, 0);
  for (std::size_t i = 0; i < orphans_.vf.size(); ++i) {
    const Index g = first_free_face(orphans_.vf[i].v, orphans_.vf[i].f);
    if (g >= 0) ++carried_start_[std::size_t(g) + 1], carrier_of_vf[i] = g;
    else uncarried_.vf.push_back(orphans_.vf[i]);
  }
  for (std::size_t i = 0; i < orphans_.ee.size(); ++i) {
    const EdgeEdgePair& p = orphans_.ee[i];
    std::tie(carrier_of_ee[i], other_of_ee[i]) = first_free_faces(p.a, p.b);
    if (carrier_of_ee[i] >= 0) ++carried_start_[std::size_t(carrier_of_ee[i]) + 1];
    else uncarried_.ee.push_back(p);
  }
  for (std::size_t f = 0; f < std::size_t(mesh_.num_faces()); ++f) carried_start_[f + 1] += carried_start_[f];
  carried_.resize(carried_start_.back());
  carried_bits_.assign(std::size_t(mesh_.num_faces()), 0);
  std::vector<std::uint32_t> next(carried_start_.begin(), carried_start_.end() - 1);
  const auto carry = [&](Index g, CarriedOrphan pair) {
    carried_[next[std::size_t(g)]++] = pair;
    carried_bits_[std::size_t(g)] |= carried_bits(pair.other);
  };
  for (std::size_t i = 0; i < orphans_.vf.size(); ++i)
    if (const Index g = carrier_of_vf[i]; g >= 0) carry(g, {orphans_.vf[i].f, orphans_.vf[i].v, -1});
  for (std::size_t i = 0; i < orphans_.ee.size(); ++i)
    if (const Index g = carrier_of_ee[i]; g >= 0) carry(g, {other_of_ee[i], orphans_.ee[i].a, orphans_.ee[i].b});
}

void Representatives::append_owned(std::span<const FacePair> candidates, UninitializedVector<VertexFacePair>& vf,
                                   UninitializedVector<EdgeEdgePair>& ee, bool simd) const {
  // for_each_pair's fixed rule without its branches: every slot is written, the end advances by the owner bit
  // (the bits are close to random, so a branch per pair mispredicts half the time and costs more than the pair).
  const std::size_t vf_begin = vf.size(), ee_begin = ee.size();
  vf.resize(vf_begin + 6 * candidates.size() + 8);  // + 8: the SIMD version stores whole vectors
  ee.resize(ee_begin + 9 * candidates.size() + 8);
  VertexFacePair* out_vf = vf.data() + vf_begin;
  EdgeEdgePair* out_ee = ee.data() + ee_begin;
  if (std::size_t n_vf = 0, n_ee = 0;
      simd && detail::gather_owned_simd(records_.data(), candidates, out_vf, out_ee, &n_vf, &n_ee)) {
    vf.resize(vf_begin + n_vf);
    ee.resize(ee_begin + n_ee);
    return;
  }
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const FacePair& p = candidates[k];
    if (k + 12 < candidates.size()) {
      const FacePair& q = candidates[k + 12];
      __builtin_prefetch(&mesh_.face(q.a));
      __builtin_prefetch(&mesh_.face(q.b));
      __builtin_prefetch(&mesh_.face_edges(q.a));
      __builtin_prefetch(&mesh_.face_edges(q.b));
      __builtin_prefetch(&owners_.owned_mask[q.b]);
    }
    const Face &ta = mesh_.face(p.a), &tb = mesh_.face(p.b);
    const auto &ea = mesh_.face_edges(p.a), &eb = mesh_.face_edges(p.b);
    const unsigned ma = owners_.owned_mask[p.a], mb = owners_.owned_mask[p.b];
    for (int j = 0; j < 3; ++j) {
      *out_vf = {ta[j], p.b};
      out_vf += (ma >> j) & 1u;
      *out_vf = {tb[j], p.a};
      out_vf += (mb >> j) & 1u;
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        *out_ee = ordered_edge_pair(ea[i], eb[j]);
        out_ee += (ma >> (3 + i)) & (mb >> (3 + j)) & 1u;
      }
  }
  vf.resize(std::size_t(out_vf - vf.data()));
  ee.resize(std::size_t(out_ee - ee.data()));
}

OrphanSet Representatives::build_first_free_orphans(const std::vector<bool>& self) const {
  // An orphan's faces are all adjacent to the first face of its first feature, so the candidates for the
  // second feature are the features of that face's neighbours (faces sharing a vertex with it).
  OrphanSet orphans;
  std::vector<Index> ring;
  auto faces_around = [&](Index face) { faces_sharing_a_vertex(mesh_, face, ring); };
  for (Index v = 0; v < mesh_.num_vertices(); ++v) {
    if (mesh_.vertex_faces(v).empty() || !self[mesh_.vertex_faces(v)[0]]) continue;
    faces_around(mesh_.vertex_faces(v)[0]);
    for (Index f : ring)
      if (!contains_vertex(mesh_.face(f), v) && first_free_face(v, f) < 0) orphans.vf.push_back({v, f});
  }
  std::vector<Index> edges;
  for (Index a = 0; a < mesh_.num_edges(); ++a) {
    if (!self[mesh_.edge_faces(a)[0]]) continue;
    faces_around(mesh_.edge_faces(a)[0]);
    edges.clear();
    for (Index g : ring)
      for (Index b : mesh_.face_edges(g))
        if (b > a) edges.push_back(b);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (Index b : edges) {
      if (shares_vertex(mesh_.edge(a), mesh_.edge(b))) continue;
      bool all_adjacent = true;
      for (Index g : mesh_.edge_faces(a))
        for (Index h : mesh_.edge_faces(b)) all_adjacent &= adjacent(g, h);
      if (all_adjacent) orphans.ee.push_back({a, b});
    }
  }
  return orphans;
}

}  // namespace ccdlab
