#pragma once
// TriMesh: the topology of a triangle mesh (no positions; those live per frame in MeshSequence).
// Built once per scene: unique undirected edges, face→edge, edge→face and vertex→face adjacency, and
// connected components. Edges are numbered as unique undirected edges sorted by (larger, smaller) vertex id,
// the convention of the shared CCD query data (../shared/data/README.md).
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace ccdlab {

using Index = std::int32_t;
using Face = std::array<Index, 3>;
/// An undirected edge, v[0] < v[1].
using Edge = std::array<Index, 2>;

/// Compressed adjacency lists: the neighbours of item i are items[offsets[i] .. offsets[i+1]).
struct Adjacency {
  std::vector<Index> offsets;
  std::vector<Index> items;
  [[nodiscard]] std::span<const Index> of(Index i) const {
    return {items.data() + offsets[i], items.data() + offsets[i + 1]};
  }
};

class TriMesh {
 public:
  TriMesh() = default;
  /// Validates and builds the topology. Throws Error (naming the face) for an index out of range, a face
  /// that repeats a vertex, or a duplicate face (same vertex set), and for a mesh too large for 32-bit
  /// feature ids (Index): more than kMaxVertices vertices or kMaxFaces faces.
  TriMesh(std::size_t num_vertices, std::vector<Face> faces);

  /// Feature ids are Index (int32): vertices and faces below 2³¹, and half-edges (3 per face) too.
  static constexpr std::size_t kMaxVertices = std::size_t(std::numeric_limits<Index>::max());
  static constexpr std::size_t kMaxFaces = kMaxVertices / 3;

  [[nodiscard]] Index num_vertices() const { return num_vertices_; }
  [[nodiscard]] Index num_faces() const { return Index(faces_.size()); }
  [[nodiscard]] Index num_edges() const { return Index(edges_.size()); }
  [[nodiscard]] const std::vector<Face>& faces() const { return faces_; }
  [[nodiscard]] const Face& face(Index f) const { return faces_[f]; }
  [[nodiscard]] const std::vector<Edge>& edges() const { return edges_; }
  [[nodiscard]] const Edge& edge(Index e) const { return edges_[e]; }
  /// The 3 edges of face f: edge j joins face(f)[j] and face(f)[(j+1)%3].
  [[nodiscard]] const std::array<Index, 3>& face_edges(Index f) const { return face_edges_[f]; }
  [[nodiscard]] std::span<const Index> edge_faces(Index e) const { return edge_faces_.of(e); }
  [[nodiscard]] std::span<const Index> vertex_faces(Index v) const { return vertex_faces_.of(v); }
  /// Component id of each face (faces connected through shared vertices), 0 .. num_components()-1.
  [[nodiscard]] const std::vector<Index>& face_components() const { return face_component_; }
  [[nodiscard]] Index num_components() const { return num_components_; }
  /// True when faces f and g share at least one vertex (or f == g).
  [[nodiscard]] bool faces_adjacent(Index f, Index g) const {
    // Branch-free (nine compares): the traversal asks this of every overlapping leaf pair, and the answers
    // are close to random.
    const Face &a = faces_[f], &b = faces_[g];
    int shared = 0;
    for (Index x : a) shared |= int(x == b[0]) | int(x == b[1]) | int(x == b[2]);
    return shared != 0;
  }
  /// Edge id joining a and b, or -1.
  [[nodiscard]] Index find_edge(Index a, Index b) const;
  /// Sum of sizes of all arrays, for reports.
  [[nodiscard]] std::size_t memory_bytes() const;

 private:
  Index num_vertices_ = 0;
  std::vector<Face> faces_;
  std::vector<Edge> edges_;
  std::vector<std::array<Index, 3>> face_edges_;
  Adjacency edge_faces_;
  Adjacency vertex_faces_;
  std::vector<Index> face_component_;
  Index num_components_ = 0;
};

/// Concatenates meshes into one topology; vertex and face ids of mesh i are offset by the sizes before it.
TriMesh concatenate(const std::vector<const TriMesh*>& meshes);

}  // namespace ccdlab
