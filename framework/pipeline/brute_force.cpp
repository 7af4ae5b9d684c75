#include "framework/pipeline/brute_force.hpp"

#include <algorithm>

#include "framework/primitive/feature_pairs.hpp"
#include "framework/primitive/static_distance.hpp"
#include "framework/narrow/narrow_phase.hpp"
#include "framework/swept/feature_bounds.hpp"

namespace ccdlab {

FacePairs brute_force_candidates(const TriMesh& mesh, const CollisionRules& rules, const AnyBvs& face_bvs,
                                 std::span<const EndBoxes> face_ends) {
  FacePairs out;
  const auto apart = [&](Index a, Index b) { return !face_ends.empty() && apart_at_both_ends(face_ends[a], face_ends[b]); };
  std::visit(
      [&](const auto& bvs) {
        for (Index a = 0; a < mesh.num_faces(); ++a)
          for (Index b = a + 1; b < mesh.num_faces(); ++b)
            if (rules.faces_may_collide(mesh, a, b) && bvs[a].overlaps(bvs[b]) && !apart(a, b)) out.push_back({a, b});
      },
      face_bvs);
  return out;
}

Contacts brute_force_contacts(const TriMesh& mesh, const CollisionRules& rules, const Positions& x_t0,
                                          const Positions& x_t1, const PrimitiveTester& tester, bool box_cull) {
  // Every pair, one at a time: the scalar narrow phase on a batch that holds them all.
  NarrowPhase narrow(mesh, tester, {NarrowMode::scalar, RepresentativeRule::fixed, {}}, [](Index) { return false; });
  PhaseTrace trace;
  FeatureBounds bounds;
  bounds.update(x_t0, x_t1, tester.thickness(), 1, trace);
  narrow.begin_step(x_t0, x_t1, bounds);
  NarrowScratch scratch;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    int bv = rules.body_of_vertex(v);
    if (bv < 0) continue;
    for (Index f = 0; f < mesh.num_faces(); ++f)
      if (!contains_vertex(mesh.face(f), v) && rules.bodies_interact(bv, rules.body_of_face(f)))
        scratch.batch.vf.push_back({v, f});
  }
  for (Index a = 0; a < mesh.num_edges(); ++a)
    for (Index b = a + 1; b < mesh.num_edges(); ++b)
      if (!shares_vertex(mesh.edge(a), mesh.edge(b)) &&
          rules.bodies_interact(rules.body_of_vertex(mesh.edge(a)[0]), rules.body_of_vertex(mesh.edge(b)[0])))
        scratch.batch.ee.push_back({a, b});
  Contacts contacts;
  NarrowCounters counters;
  narrow.run(scratch, contacts, counters, box_cull);
  sort_contacts(contacts);
  return contacts;
}

void compute_face_bvs(const TriMesh& mesh, const Positions& x0, const Positions& x1, double thickness, AnyBvs& out,
                      int threads, PhaseTrace* trace) {
  PhaseTrace unused;
  FeatureBounds vertex_dops;
  vertex_dops.update(x0, x1, thickness, threads, trace ? *trace : unused);
  std::visit(
      [&](auto& bvs) {
        using BV = typename std::decay_t<decltype(bvs)>::value_type;
        bvs.resize(mesh.num_faces());
        const SweptFaceBv<BV> swept{mesh, vertex_dops};
        parallel_chunks(std::size_t(mesh.num_faces()), kFaceChunk, threads, trace ? *trace : unused,
                        [&](std::size_t b, std::size_t e, int) {
                          for (std::size_t f = b; f < e; ++f) bvs[f] = swept(Index(f));
                        });
      },
      out);
}

std::vector<EndBoxes> compute_face_end_boxes(const TriMesh& mesh, const Positions& x0, const Positions& x1,
                                             double thickness, const CullReach& reach) {
  PhaseTrace unused;
  FeatureBounds vertex_dops;
  vertex_dops.update(x0, x1, thickness, 1, unused);
  const double r = end_boxes_reach(reach.abs, reach.rel, vertex_dops.scene_extent()) / 2;
  std::vector<EndBoxes> out(std::size_t(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) out[std::size_t(f)] = face_end_boxes(vertex_dops.frame_points(), mesh.face(f), r);
  return out;
}

}  // namespace ccdlab
