#pragma once
// Contact records and the query types of the elementary CCD tests. Vocabulary (design.md): `_t0`/`_t1` for
// the two ends of a step; `v, f0 f1 f2` for vertex–face; `ea0 ea1, eb0 eb1` for edge–edge.
#include <array>
#include <compare>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

/// Vertex v moving against the triangle (f0, f1, f2), linear motion over t ∈ [0, 1].
struct VertexFaceQuery {
  Vec3 v_t0, f0_t0, f1_t0, f2_t0;
  Vec3 v_t1, f0_t1, f1_t1, f2_t1;
};

/// Edge (ea0, ea1) moving against edge (eb0, eb1), linear motion over t ∈ [0, 1].
struct EdgeEdgeQuery {
  Vec3 ea0_t0, ea1_t0, eb0_t0, eb1_t0;
  Vec3 ea0_t1, ea1_t1, eb0_t1, eb1_t1;
};

/// Which part of a tester decided a query (counted by the pipeline and `ccdlab validate`).
enum class TestRoute : std::uint8_t {
  main = 0,      ///< the tester's own method
  filter = 1,    ///< a cheap certified filter in front of it (`filtered`, the prefilter of `exact`)
  fallback = 2,  ///< the method could not decide and fell back (`conservative`: reported hit or exact)
};

/// Result of one elementary test. "No contact" is hit == false (toi and coords then meaningless).
struct CcdHit {
  bool hit = false;
  double toi = 1.0;                 ///< earliest time of contact in [0, 1] (a lower bound for `conservative`)
  std::array<double, 2> coords{};   ///< VF: barycentric weights of f1, f2; EE: parameters on edge a, edge b
  TestRoute route = TestRoute::main;
};

/// The features at time t of a contact: VF barycentric weights of f1, f2 of the closest face point; EE the
/// parameters of the closest points on edges a and b (what CcdHit::coords holds).
std::array<double, 2> contact_coords(const VertexFaceQuery& q, double t);
std::array<double, 2> contact_coords(const EdgeEdgeQuery& q, double t);

enum class ContactKind : std::uint8_t { vf = 0, ee = 1 };

/// One colliding feature pair.
///  VF: feature_a = vertex id, feature_b = face id, vertices = (v, f0, f1, f2)
///  EE: feature_a < feature_b = edge ids,           vertices = (ea0, ea1, eb0, eb1) of edges a, b
struct Contact {
  ContactKind kind;
  Index feature_a;
  Index feature_b;
  std::array<Index, 4> vertices;
  double toi;
  std::array<double, 2> coords;

  /// Identity of the feature pair (not its time): what must be equal across schedulers.
  [[nodiscard]] auto key() const { return std::tuple(kind, feature_a, feature_b); }
};

/// A step's contacts. Growing the list constructs nothing, and a large one lives in huge pages
/// (framework/util/memory.hpp): contacts grown per thread and merged would otherwise touch many fresh pages.
using Contacts = UninitializedVector<Contact>;

/// The unit normal of a contact at its time of contact, the features moving linearly from x_t0 to x_t1: the
/// face's normal (f1 − f0) × (f2 − f0) for VF, edge a × edge b for EE; zero where the face is degenerate or the
/// edges parallel at that time.
Vec3 contact_normal(const Contact& c, const Positions& x_t0, const Positions& x_t1);

/// What sort_contacts works in, kept by a caller that sorts every step: fresh pages for these buffers at each
/// step cost more than the sort itself (page faults).
struct ContactSortScratch {
  struct Keyed {
    std::uint64_t key;       ///< Contact::key() packed: kind, feature_a, feature_b (ContactSortScratch::Part)
    const Contact* contact;  ///< where it is
  };
  /// One part's sorted keys. Sorted in the bits its own largest ids need, then rewritten to one layout for all
  /// parts (kind in bit 62, feature_a in bits 31–61, feature_b in bits 0–30), which the merge compares.
  struct Part {
    std::vector<Keyed> keys, swap;
    std::vector<std::size_t> histogram;
    bool packed = false;  ///< every key packed (ids ≥ 0 and < 2³¹, a known kind); else the comparison sort
  };
  std::vector<Part> parts;
  std::vector<Contact> moved;
};

/// Sorts contacts by feature identity (Contact::key()).
void sort_contacts(Contacts& contacts, ContactSortScratch& scratch);
void sort_contacts(Contacts& contacts);
/// Runs task(i) for every i in [0, n): in turn by default; a caller with threads runs them at once.
using PartRunner = std::function<void(std::size_t n, const std::function<void(std::size_t)>& task)>;
/// The contacts of all `parts` (the threads' lists of a step), sorted by feature identity, into `out` (its
/// contents replaced): each part's keys radix-sorted on their own (through `run_parts`, so by several threads at
/// once), then merged, each contact copied once, to its place. The keys are unique within a step, so the order
/// does not depend on how the contacts were split into parts.
void sort_contacts_into(std::span<const std::span<const Contact>> parts, Contacts& out, ContactSortScratch& scratch,
                        const PartRunner& run_parts = {});

/// 64-bit FNV-1a hash of the sorted (kind, feature_a, feature_b) of all contacts: equal contact sets give
/// equal hashes whatever the scheduler or thread count. `seed` chains hashes across steps.
std::uint64_t contact_set_hash(std::span<const Contact> sorted_contacts, std::uint64_t seed = 14695981039346656037ull);

std::string_view to_string(ContactKind kind);

}  // namespace ccdlab
