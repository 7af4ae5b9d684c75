#include "framework/primitive/feature_pairs.hpp"

#include <algorithm>

namespace ccdlab {

void faces_sharing_a_vertex(const TriMesh& mesh, Index face, std::vector<Index>& ring) {
  ring.clear();
  for (Index u : mesh.face(face))
    for (Index g : mesh.vertex_faces(u)) ring.push_back(g);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
}

Ownership assign_owners(const TriMesh& mesh) {
  Ownership own;
  own.vertex_owner.assign(mesh.num_vertices(), -1);
  own.edge_owner.assign(mesh.num_edges(), -1);
  own.owned_mask.assign(mesh.num_faces(), 0);
  std::vector<int> load(mesh.num_faces(), 0);
  auto least_loaded = [&](std::span<const Index> faces) {
    Index best = faces[0];
    for (Index f : faces)
      if (load[f] < load[best]) best = f;
    return best;
  };
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    auto faces = mesh.vertex_faces(v);
    if (faces.empty()) continue;
    Index f = least_loaded(faces);
    own.vertex_owner[v] = f;
    ++load[f];
    for (int j = 0; j < 3; ++j)
      if (mesh.face(f)[j] == v) own.owned_mask[f] |= std::uint8_t(1u << j);
  }
  for (Index e = 0; e < mesh.num_edges(); ++e) {
    Index f = least_loaded(mesh.edge_faces(e));
    own.edge_owner[e] = f;
    ++load[f];
    for (int j = 0; j < 3; ++j)
      if (mesh.face_edges(f)[j] == e) own.owned_mask[f] |= std::uint8_t(1u << (3 + j));
  }
  return own;
}

}  // namespace ccdlab
