#include "framework/mesh/tri_mesh.hpp"

#include <algorithm>
#include <numeric>

#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

Adjacency build_adjacency(Index num_items, const std::vector<std::pair<Index, Index>>& item_to_neighbour) {
  Adjacency adj;
  adj.offsets.assign(num_items + 1, 0);
  for (auto [item, n] : item_to_neighbour) ++adj.offsets[item + 1];
  std::partial_sum(adj.offsets.begin(), adj.offsets.end(), adj.offsets.begin());
  adj.items.resize(item_to_neighbour.size());
  std::vector<Index> fill(adj.offsets.begin(), adj.offsets.end() - 1);
  for (auto [item, n] : item_to_neighbour) adj.items[fill[item]++] = n;
  return adj;
}

struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(Index n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(Index a, Index b) { parent[find(a)] = find(b); }
};

}  // namespace

TriMesh::TriMesh(std::size_t num_vertices, std::vector<Face> faces) : faces_(std::move(faces)) {
  if (num_vertices > kMaxVertices)
    fail("{} vertices: more than ccdlab's 32-bit vertex ids allow ({})", num_vertices, kMaxVertices);
  if (faces_.size() > kMaxFaces)
    fail("{} faces: more than ccdlab's 32-bit feature ids allow ({})", faces_.size(), kMaxFaces);
  num_vertices_ = Index(num_vertices);
  const Index nf = num_faces();
  for (Index f = 0; f < nf; ++f) {
    const Face& t = faces_[f];
    for (Index v : t)
      if (v < 0 || v >= num_vertices_)
        fail("face {}: vertex index {} out of range [0, {})", f, v, num_vertices_);
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      fail("face {}: degenerate, repeats a vertex ({} {} {})", f, t[0], t[1], t[2]);
  }
  // Duplicate faces (same vertex set in any order) make the ownership rule ill-defined: reject them.
  if (nf > 1) {
    std::vector<std::pair<Face, Index>> sorted(std::size_t(nf), {Face{}, 0});
    for (Index f = 0; f < nf; ++f) {
      Face t = faces_[f];
      std::sort(t.begin(), t.end());
      sorted[f] = {t, f};
    }
    std::sort(sorted.begin(), sorted.end());
    for (Index i = 1; i < nf; ++i)
      if (sorted[i].first == sorted[i - 1].first)
        fail("face {}: duplicate of face {} (vertices {} {} {})", sorted[i].second, sorted[i - 1].second,
             sorted[i].first[0], sorted[i].first[1], sorted[i].first[2]);
  }

  // Unique undirected edges, sorted by (larger, smaller) vertex id.
  std::vector<std::pair<Edge, Index>> half(3 * std::size_t(nf));  // (edge (hi, lo), face*3 + j)
  for (Index f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j) {
      Index a = faces_[f][j], b = faces_[f][(j + 1) % 3];
      half[3 * f + j] = {Edge{std::max(a, b), std::min(a, b)}, 3 * f + j};
    }
  std::sort(half.begin(), half.end());
  face_edges_.resize(nf);
  std::vector<std::pair<Index, Index>> edge_face_pairs;
  edge_face_pairs.reserve(half.size());
  for (std::size_t i = 0; i < half.size(); ++i) {
    if (i == 0 || half[i].first != half[i - 1].first)
      edges_.push_back(Edge{half[i].first[1], half[i].first[0]});
    Index e = num_edges() - 1;
    Index f = half[i].second / 3;
    face_edges_[f][half[i].second % 3] = e;
    edge_face_pairs.emplace_back(e, f);
  }
  edge_faces_ = build_adjacency(num_edges(), edge_face_pairs);

  std::vector<std::pair<Index, Index>> vertex_face_pairs;
  vertex_face_pairs.reserve(3 * std::size_t(nf));
  for (Index f = 0; f < nf; ++f)
    for (Index v : faces_[f]) vertex_face_pairs.emplace_back(v, f);
  std::sort(vertex_face_pairs.begin(), vertex_face_pairs.end());
  vertex_faces_ = build_adjacency(num_vertices_, vertex_face_pairs);

  UnionFind uf(num_vertices_);
  for (const Face& t : faces_) {
    uf.unite(t[0], t[1]);
    uf.unite(t[1], t[2]);
  }
  std::vector<Index> root_id(num_vertices_, -1);
  face_component_.resize(nf);
  for (Index f = 0; f < nf; ++f) {
    Index r = uf.find(faces_[f][0]);
    if (root_id[r] < 0) root_id[r] = num_components_++;
    face_component_[f] = root_id[r];
  }
}

Index TriMesh::find_edge(Index a, Index b) const {
  if (a < 0 || b < 0 || a >= num_vertices_ || b >= num_vertices_) return -1;
  for (Index f : vertex_faces(a))
    for (Index e : face_edges_[f]) {
      const Edge& ed = edges_[e];
      if ((ed[0] == a && ed[1] == b) || (ed[0] == b && ed[1] == a)) return e;
    }
  return -1;
}

std::size_t TriMesh::memory_bytes() const {
  return faces_.size() * sizeof(Face) + edges_.size() * sizeof(Edge) + face_edges_.size() * sizeof(face_edges_[0]) +
         (edge_faces_.items.size() + edge_faces_.offsets.size() + vertex_faces_.items.size() +
          vertex_faces_.offsets.size() + face_component_.size()) *
             sizeof(Index);
}

TriMesh concatenate(const std::vector<const TriMesh*>& meshes) {
  std::vector<Face> faces;
  Index offset = 0;
  for (const TriMesh* m : meshes) {
    for (Face f : m->faces()) faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
    offset += m->num_vertices();
  }
  return TriMesh(offset, std::move(faces));
}

}  // namespace ccdlab
