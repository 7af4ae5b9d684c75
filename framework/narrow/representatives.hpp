#pragma once
// Which candidate face pair tests a feature pair: the representative rule (design.md, "gather").
//
// `fixed` (primitive/feature_pairs.hpp, Tang et al. 2009): every vertex and edge has one owner face; (v, f) is
// tested by the candidate (owner(v), f). When the owner is adjacent to f, the traversal never reports that
// face pair, so the pair is an orphan, tested every step: on a tangled 146K-triangle step, ~10^6 of them.
//
// `first_free` (what the ICCD release does at test time): (v, f) is tested by (g, f), g the FIRST face around v,
// in the mesh's vertex_faces order, that is not adjacent to f; (a, b), a < b, by the first non-adjacent (g, h)
// of edge_faces(a) × edge_faces(b) in lexicographic order. Only pairs whose every incident face pair is
// adjacent are orphans: a few per vertex of high valence. Exactly once: a feature pair has one first face
// pair, and the traversal reports each candidate once. None lost: a pair that passes stage 1
// (feature_bounds.hpp) has overlapping leaves for EVERY incident face pair, so its first non-adjacent one is a
// candidate; normal-cone culling drops a candidate only inside one skipped patch, where no two non-adjacent
// features can touch (hierarchy/normal_cones.hpp).
//
// `fixed` with carried orphans (the two combined, in the steps where it pays: NarrowPhase::begin_step): the
// owned pairs as `fixed`, and each orphan through first_free's face pair instead of the orphan loop; only the
// orphans with no non-adjacent face pair stay in the loop. Exactly once and none lost by the two arguments
// above: an orphan's owner pair is never a candidate, and its first free pair is the only candidate that
// carries it. Stage 0 (triangle_filter.hpp) drops a candidate only when no pair of its features can touch,
// so it may drop the orphans a candidate carries with it.
#include <algorithm>
#include <span>
#include <string_view>
#include <utility>

#include "framework/mesh/tri_mesh.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/util/memory.hpp"
#include "framework/util/named_values.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

enum class RepresentativeRule { fixed, first_free };

/// Face `other`'s two bits in a carrier's 64-bit signature (a Bloom filter: Representatives::carried_bits_):
/// a candidate reads a face's list of carried orphans only when both are set (one bit sends too many lookups to
/// a list that does not hold the face). A
/// carrier's others lie two rings around it, at nearby ids, so the bits come from a multiplicative hash, not
/// from the id's low bits.
constexpr std::uint64_t carried_bits(Index other) {
  const std::uint32_t h = std::uint32_t(other) * 0x9E3779B1u;
  return (1ull << (h >> 26)) | (1ull << ((h >> 20) & 63u));
}

/// What the fixed rule's gather reads of a face, in one 32-byte line: its corners and edges (the mesh's order),
/// its owner bits (Ownership::owned_mask) and its own id.
struct alignas(32) GatherRecord {
  Index corner[3];
  Index edge[3];
  std::int32_t owned_mask;
  Index self;
};
static_assert(sizeof(GatherRecord) == 32);

/// A pair of the fixed rule's orphan set, carried in the steps that allow it (NarrowPhase::begin_step) by a
/// non-adjacent face pair of its features instead: the first one in first_free's order, (carrier, other), the
/// carrier holding v or edge a. VF (v = a, f = other) when b < 0; else EE (a, b), a < b. Stored under the
/// carrier; a candidate looks in both of its faces' lists for the other face (the pair beside the face: a hit
/// reads no second line).
struct CarriedOrphan {
  Index other;
  Index a;
  Index b;
};

/// The EE pair of edges x and y, smaller id first, without a branch (g++ makes std::min/max jumps here, taken at
/// random). Ids are non-negative int32, so y − x cannot overflow; d = min(0, y − x).
constexpr EdgeEdgePair ordered_edge_pair(Index x, Index y) {
  const Index diff = y - x, d = diff & (diff >> 31);
  return {x + d, y - d};
}

namespace detail {
/// The fixed rule's gather in SIMD (gather_simd.cpp) on CPUs with AVX2 or AVX-512: writes the pairs of
/// append_pairs, in its order, and returns true; false on other CPUs (nothing written). Writes whole vectors:
/// out_vf needs 6 slots per candidate + 8, out_ee 9 per candidate + 8.
bool gather_owned_simd(const GatherRecord* rec, std::span<const FacePair> candidates, VertexFacePair* out_vf,
                       EdgeEdgePair* out_ee, std::size_t* n_vf, std::size_t* n_ee);
}  // namespace detail
/// narrow.representative's names: the one list every reader, message and choice list takes.
inline constexpr NamedValues<RepresentativeRule, 2> kRepresentativeRules{
    {{{"fixed", RepresentativeRule::fixed}, {"first_free", RepresentativeRule::first_free}}}};
[[nodiscard]] inline std::string_view to_string(RepresentativeRule r) { return kRepresentativeRules.name_of(r); }

class Representatives {
 public:
  /// `self_collision(face)`: whether the face's body collides with itself (orphans exist only there).
  template <class Pred>
  Representatives(const TriMesh& mesh, RepresentativeRule rule, Pred&& self_collision);

  [[nodiscard]] RepresentativeRule rule() const { return rule_; }
  [[nodiscard]] const Ownership& owners() const { return owners_; }
  [[nodiscard]] const OrphanSet& orphans() const { return orphans_; }
  /// fixed rule: the orphans no non-adjacent face pair of their features can carry (a few per vertex of high
  /// valence); the rest can ride with the candidates (append_pairs' `carry_orphans`). Empty for first_free.
  [[nodiscard]] const OrphanSet& uncarried_orphans() const { return uncarried_; }
  /// Whether some orphan can be carried (fixed rule with a non-empty orphan set).
  [[nodiscard]] bool carries_orphans() const { return !carried_.empty(); }
  /// A face incident to the vertex / edge, used to place an orphan in a normal-cone patch.
  [[nodiscard]] Index face_of_vertex(Index v) const;
  [[nodiscard]] Index face_of_edge(Index e) const;

  /// Appends the feature pairs that the non-adjacent candidates represent, candidate by candidate.
  /// `simd = false` runs the plain loop of the fixed rule even where the SIMD one could run (tests).
  /// `carry_orphans` (fixed rule): also the orphans each candidate carries (CarriedOrphan), after the owned
  /// pairs; returns how many. The caller then tests uncarried_orphans() instead of orphans().
  std::size_t append_pairs(std::span<const FacePair> candidates, UninitializedVector<VertexFacePair>& vf,
                           UninitializedVector<EdgeEdgePair>& ee, bool simd = true, bool carry_orphans = false) const;
  /// The feature pairs that the non-adjacent candidate (fa, fb) represents (the reference append_pairs follows).
  template <class OnVf, class OnEe>
  void for_each_pair(Index fa, Index fb, OnVf&& on_vf, OnEe&& on_ee) const;

 private:
  [[nodiscard]] bool adjacent(Index f, Index g) const {
    const Face &a = mesh_.face(f), &b = mesh_.face(g);
    bool shared = false;
    for (Index u : a) shared |= int(u == b[0]) | int(u == b[1]) | int(u == b[2]);
    return shared;
  }
  /// first_free: the face pair that represents (v, f) / (a, b) with a < b, or -1 when every one is adjacent.
  [[nodiscard]] Index first_free_face(Index v, Index f) const {
    for (Index g : mesh_.vertex_faces(v))
      if (!adjacent(g, f)) return g;
    return -1;
  }
  [[nodiscard]] std::pair<Index, Index> first_free_faces(Index a, Index b) const {
    for (Index g : mesh_.edge_faces(a))
      for (Index h : mesh_.edge_faces(b))
        if (!adjacent(g, h)) return {g, h};
    return {-1, -1};
  }
  [[nodiscard]] bool first_free_is(Index a, Index b, Index fa, Index fb) const {
    return first_free_faces(a, b) == std::pair(fa, fb);
  }
  OrphanSet build_first_free_orphans(const std::vector<bool>& self) const;
  /// The fixed rule's pairs of the candidates (SIMD where the CPU has it and `simd`).
  void append_owned(std::span<const FacePair> candidates, UninitializedVector<VertexFacePair>& vf,
                    UninitializedVector<EdgeEdgePair>& ee, bool simd) const;
  /// fixed rule: sorts orphans_ into carried_ (by carrier face) and uncarried_.
  void build_carried_orphans();
  /// Appends the orphans that face `carrier` carries with face `other`; returns how many.
  std::size_t append_carried(Index carrier, Index other, UninitializedVector<VertexFacePair>& vf,
                             UninitializedVector<EdgeEdgePair>& ee) const;
  /// first_free, fast path: whether candidate face `fa` (v is its corner j) represents (v, fb). Most answers
  /// need no walk: fa comes first around v (rank 0), or the first face around v is already free of fb.
  [[nodiscard]] bool represents_vf(Index fa, int j, Index v, Index fb) const {
    if (corner_rank_[3 * std::size_t(fa) + j] == 0) return true;
    if (!adjacent(mesh_.vertex_faces(v)[0], fb)) return false;
    return first_free_face(v, fb) == fa;
  }
  /// first_free, fast path for edges x < y of the candidate faces fx, fy (edge slots i, j of those faces).
  [[nodiscard]] bool represents_ee(Index x, Index fx, int i, Index y, Index fy, int j) const {
    if (edge_rank_[3 * std::size_t(fx) + i] == 0 && edge_rank_[3 * std::size_t(fy) + j] == 0) return true;
    if (!adjacent(mesh_.edge_faces(x)[0], mesh_.edge_faces(y)[0])) return false;
    return first_free_is(x, y, fx, fy);
  }

  const TriMesh& mesh_;
  RepresentativeRule rule_;
  Ownership owners_;  ///< fixed rule only
  UninitializedVector<GatherRecord> records_;  ///< fixed rule only: per face, for the SIMD gather (huge pages when large)
  // first_free only: position of face f in vertex_faces(face(f)[j]) / edge_faces(face_edges(f)[j]), per corner
  // (3 per face), capped at 255 (only 0 matters).
  std::vector<std::uint8_t> corner_rank_;
  std::vector<std::uint8_t> edge_rank_;
  OrphanSet orphans_;
  // fixed rule: the orphans, by the face that carries them (carried_start_[f] .. carried_start_[f + 1]), each
  // face's signature of the faces it carries them with, and the orphans no face pair carries.
  std::vector<std::uint32_t> carried_start_;
  std::vector<CarriedOrphan> carried_;
  std::vector<std::uint64_t> carried_bits_;
  OrphanSet uncarried_;
};

template <class Pred>
Representatives::Representatives(const TriMesh& mesh, RepresentativeRule rule, Pred&& self_collision)
    : mesh_(mesh), rule_(rule) {
  if (rule_ == RepresentativeRule::fixed) {
    owners_ = assign_owners(mesh);
    orphans_ = build_orphan_set(mesh, owners_, self_collision);
    // One large (huge-page) allocation even for a small mesh: in 4 KiB pages the records cost a fault per 128
    // faces and take the freed memory the step's first arrays would reuse otherwise.
    records_.reserve(std::max(std::size_t(mesh.num_faces()), kLargeAllocation / sizeof(GatherRecord)));
    records_.resize(std::size_t(mesh.num_faces()));
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      GatherRecord& r = records_[std::size_t(f)];
      for (int j = 0; j < 3; ++j) r.corner[j] = mesh.face(f)[j], r.edge[j] = mesh.face_edges(f)[j];
      r.owned_mask = owners_.owned_mask[std::size_t(f)];
      r.self = f;
    }
    build_carried_orphans();
  } else {
    corner_rank_.assign(3 * std::size_t(mesh.num_faces()), 255);
    edge_rank_.assign(3 * std::size_t(mesh.num_faces()), 255);
    for (Index f = 0; f < mesh.num_faces(); ++f)
      for (int j = 0; j < 3; ++j) {
        const auto around = mesh.vertex_faces(mesh.face(f)[j]);
        const auto sides = mesh.edge_faces(mesh.face_edges(f)[j]);
        for (std::size_t r = 0; r < around.size() && r < 255; ++r)
          if (around[r] == f) corner_rank_[3 * std::size_t(f) + j] = std::uint8_t(r);
        for (std::size_t r = 0; r < sides.size() && r < 255; ++r)
          if (sides[r] == f) edge_rank_[3 * std::size_t(f) + j] = std::uint8_t(r);
      }
    std::vector<bool> self(mesh.num_faces());
    for (Index f = 0; f < mesh.num_faces(); ++f) self[f] = self_collision(f);
    orphans_ = build_first_free_orphans(self);
  }
}

template <class OnVf, class OnEe>
void Representatives::for_each_pair(Index fa, Index fb, OnVf&& on_vf, OnEe&& on_ee) const {
  const Face &ta = mesh_.face(fa), &tb = mesh_.face(fb);
  const auto &ea = mesh_.face_edges(fa), &eb = mesh_.face_edges(fb);
  if (rule_ == RepresentativeRule::fixed) {
    const std::uint8_t ma = owners_.owned_mask[fa], mb = owners_.owned_mask[fb];
    for (int j = 0; j < 3; ++j) {
      if (ma & (1u << j)) on_vf(ta[j], fb);
      if (mb & (1u << j)) on_vf(tb[j], fa);
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if ((ma & (8u << i)) && (mb & (8u << j))) on_ee(std::min(ea[i], eb[j]), std::max(ea[i], eb[j]));
    return;
  }
  for (int j = 0; j < 3; ++j) {
    if (represents_vf(fa, j, ta[j], fb)) on_vf(ta[j], fb);
    if (represents_vf(fb, j, tb[j], fa)) on_vf(tb[j], fa);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Index a = ea[i], b = eb[j];
      if (a < b ? represents_ee(a, fa, i, b, fb, j) : represents_ee(b, fb, j, a, fa, i)) on_ee(std::min(a, b), std::max(a, b));
    }
}

}  // namespace ccdlab
