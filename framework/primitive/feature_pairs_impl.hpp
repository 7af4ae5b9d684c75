#pragma once
// Template implementation of build_orphan_set (included by feature_pairs.hpp).
#include <algorithm>

namespace ccdlab {

template <class Pred>
OrphanSet build_orphan_set(const TriMesh& mesh, const Ownership& own, Pred&& self_collision) {
  OrphanSet orphans;
  std::vector<Index> ring;  // faces adjacent to (sharing a vertex with) the owner face, incl. itself
  auto faces_around = [&](Index face) { faces_sharing_a_vertex(mesh, face, ring); };
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    Index o = own.vertex_owner[v];
    if (o < 0 || !self_collision(o)) continue;
    faces_around(o);
    for (Index g : ring)
      if (!contains_vertex(mesh.face(g), v)) orphans.vf.push_back({v, g});
  }
  for (Index a = 0; a < mesh.num_edges(); ++a) {
    Index o = own.edge_owner[a];
    if (!self_collision(o)) continue;
    faces_around(o);
    for (Index g : ring)
      for (int j = 0; j < 3; ++j) {
        Index b = mesh.face_edges(g)[j];
        // each unordered pair is reached from both sides: keep a < b
        if (b > a && own.edge_owner[b] == g && !shares_vertex(mesh.edge(a), mesh.edge(b)))
          orphans.ee.push_back({a, b});
      }
  }
  return orphans;
}

}  // namespace ccdlab
