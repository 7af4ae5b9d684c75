#pragma once
// Feature pairs of a triangle pair and the ICCD ownership rule (Tang et al. 2009, "representative
// triangles"; the paper's "reduced set"). Two triangles produce 15 elementary tests (6 VF + 9 EE), but
// neighbouring triangles share vertices and edges, so testing every candidate pair's 15 would repeat tests.
// Each vertex and each edge is assigned to exactly one incident face (its owner). A candidate face pair
// (fa, fb) then tests only the features each face owns:
//     VF: owned vertices of fa × face fb,  owned vertices of fb × face fa
//     EE: owned edges of fa × owned edges of fb
// Every vertex–face pair (v, f), v ∉ f, is thus reached only through the pair (owner(v), f), and every
// edge–edge pair (a, b) only through (owner(a), owner(b)). When those two faces are adjacent (share a vertex),
// the traversal skips them, so such feature pairs would be lost: they form the ORPHAN SET, built once per
// topology and tested every step. Together: each feature pair is tested at most once, and none is lost.
#include <cstdint>
#include <vector>

#include "framework/mesh/tri_mesh.hpp"

namespace ccdlab {

struct Ownership {
  std::vector<Index> vertex_owner;       ///< face owning each vertex
  std::vector<Index> edge_owner;         ///< face owning each edge
  std::vector<std::uint8_t> owned_mask;  ///< per face: bit j = owns vertex face(f)[j]; bit 3+j = owns edge j
};

/// Assigns every vertex and edge to one incident face, greedily balancing the number of features per face.
/// Deterministic. Isolated vertices (in no face) get owner -1 and take part in no test.
Ownership assign_owners(const TriMesh& mesh);

struct VertexFacePair {
  Index v;
  Index f;
  auto operator<=>(const VertexFacePair&) const = default;
};
struct EdgeEdgePair {
  Index a;  ///< a < b
  Index b;
  auto operator<=>(const EdgeEdgePair&) const = default;
};

/// Feature pairs of adjacent faces that no non-adjacent candidate pair covers.
struct OrphanSet {
  std::vector<VertexFacePair> vf;
  std::vector<EdgeEdgePair> ee;
};

/// The faces sharing a vertex with `face` (itself included), sorted, into `ring`.
void faces_sharing_a_vertex(const TriMesh& mesh, Index face, std::vector<Index>& ring);

/// Builds the orphan set of the faces for which `self_collision(face)` is true (a body with self-collision).
template <class Pred>
OrphanSet build_orphan_set(const TriMesh& mesh, const Ownership& own, Pred&& self_collision);

/// Feature pairs of one mesh that are candidates at all: VF with v ∉ f, EE with no shared vertex.
[[nodiscard]] inline bool shares_vertex(const Edge& a, const Edge& b) {
  return a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1];
}
[[nodiscard]] inline bool contains_vertex(const Face& f, Index v) { return f[0] == v || f[1] == v || f[2] == v; }

}  // namespace ccdlab

#include "framework/primitive/feature_pairs_impl.hpp"
