// The ownership rule and the orphan set: every vertex–face and edge–edge feature pair is tested at most once,
// and every pair brute force finds colliding is tested.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

PipelineStrategies default_strategies(int k, NarrowOptions narrow = {}) {
  PipelineStrategies s;
  s.k = k;
  s.narrow = narrow;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({"sequential", {}});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  return s;
}

/// One step of a crumpled grid moving randomly, recording every feature pair gathered; returns them sorted
/// (checked: each at most once, none joining a feature to itself) with the step's candidates.
struct Gathered {
  std::vector<VertexFacePair> vf;
  std::vector<EdgeEdgePair> ee;
  std::set<std::pair<Index, Index>> candidates;
  [[nodiscard]] bool is_candidate(Index f, Index g) const { return candidates.count({std::min(f, g), std::max(f, g)}) > 0; }
};
Gathered gather_one_step(CcdPipeline& pipeline, const MeshData& g, unsigned seed, Positions* x0_out = nullptr,
                         Positions* x1_out = nullptr) {
  const TriMesh& mesh = pipeline.mesh();
  pipeline.set_record_tested_pairs(true);
  pipeline.keep_candidates(true);
  std::mt19937 rng(seed);
  Positions x0 = test::crumple(g.positions, rng, 0.02), x1 = x0;
  std::uniform_real_distribution<double> u(-1, 1);
  for (Vec3& p : x1) p += 0.12 * Vec3(u(rng), u(rng), u(rng));
  StepResult r = pipeline.step(x0, x1);
  Gathered out{r.tested_vf, r.tested_ee, {}};
  std::sort(out.vf.begin(), out.vf.end());
  std::sort(out.ee.begin(), out.ee.end());
  EXPECT_EQ(std::adjacent_find(out.vf.begin(), out.vf.end()), out.vf.end()) << "a VF pair was tested twice";
  EXPECT_EQ(std::adjacent_find(out.ee.begin(), out.ee.end()), out.ee.end()) << "an EE pair was tested twice";
  for (const auto& p : out.vf) EXPECT_FALSE(contains_vertex(mesh.face(p.f), p.v));
  for (const auto& p : out.ee) EXPECT_FALSE(shares_vertex(mesh.edge(p.a), mesh.edge(p.b)));
  for (const FacePair& p : pipeline.last_candidates().pairs.flatten()) out.candidates.insert({p.a, p.b});
  if (x0_out) *x0_out = std::move(x0);
  if (x1_out) *x1_out = std::move(x1);
  return out;
}

/// first_free's face pair of (v, f): the first face around v not adjacent to f, or -1.
Index first_free_vf(const TriMesh& mesh, Index v, Index f) {
  for (Index h : mesh.vertex_faces(v))
    if (!mesh.faces_adjacent(h, f)) return h;
  return -1;
}
/// first_free's face pair of (a, b): the first non-adjacent one of edge_faces(a) × edge_faces(b), or {-1, -1}.
std::pair<Index, Index> first_free_ee(const TriMesh& mesh, Index a, Index b) {
  for (Index fa : mesh.edge_faces(a))
    for (Index fb : mesh.edge_faces(b))
      if (!mesh.faces_adjacent(fa, fb)) return {fa, fb};
  return {-1, -1};
}

/// Every pair brute force finds colliding is among the gathered ones.
void expect_every_contact_gathered(const CcdPipeline& pipeline, const Gathered& gathered, const Positions& x0, const Positions& x1) {
  auto truth = brute_force_contacts(pipeline.mesh(), pipeline.rules(), x0, x1, *pipeline.strategies().tester);
  ASSERT_GT(truth.size(), 5u);
  for (const Contact& c : truth) {
    if (c.kind == ContactKind::vf)
      EXPECT_TRUE(std::binary_search(gathered.vf.begin(), gathered.vf.end(), VertexFacePair{c.feature_a, c.feature_b}));
    else
      EXPECT_TRUE(std::binary_search(gathered.ee.begin(), gathered.ee.end(), EdgeEdgePair{c.feature_a, c.feature_b}));
  }
}

TEST(Ownership, EveryFeatureHasOneIncidentOwner) {
  MeshData g = test::grid(7, 5);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  Ownership own = assign_owners(mesh);
  std::vector<int> owned_features(mesh.num_faces(), 0);
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    Index f = own.vertex_owner[v];
    ASSERT_TRUE(contains_vertex(mesh.face(f), v));
    ++owned_features[f];
  }
  for (Index e = 0; e < mesh.num_edges(); ++e) {
    auto faces = mesh.edge_faces(e);
    ASSERT_NE(std::find(faces.begin(), faces.end(), own.edge_owner[e]), faces.end());
    ++owned_features[own.edge_owner[e]];
  }
  int mask_bits = 0;
  for (auto m : own.owned_mask) mask_bits += __builtin_popcount(m);
  EXPECT_EQ(mask_bits, mesh.num_vertices() + mesh.num_edges());
  // Balanced: V + E = 48 + 117 features over 70 faces (2.4 each); the greedy rule keeps every face at <= 4.
  EXPECT_LE(*std::max_element(owned_features.begin(), owned_features.end()), 4);
}

TEST(Ownership, FeaturePairsAreTestedExactlyOnceAndNoneIsLost) {
  MeshData g = test::grid(8, 8);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  for (int k : {6, 18}) {
    CcdPipeline pipeline(mesh, single_cloth_body(mesh), default_strategies(k));
    Positions x0, x1;
    const Gathered gathered = gather_one_step(pipeline, g, 5 + k, &x0, &x1);
    const auto& vf = gathered.vf;
    const auto& ee = gathered.ee;

    // Exactly the pairs the rule promises: orphans, plus the owned features of every candidate face pair.
    const Ownership& own = pipeline.representatives().owners();
    auto is_candidate = [&](Index f, Index g2) { return gathered.is_candidate(f, g2); };
    std::size_t expected_vf = 0, expected_ee = 0;
    for (Index v = 0; v < mesh.num_vertices(); ++v)
      for (Index f = 0; f < mesh.num_faces(); ++f) {
        if (contains_vertex(mesh.face(f), v)) continue;
        bool orphan = mesh.faces_adjacent(own.vertex_owner[v], f);
        bool expect = orphan || is_candidate(own.vertex_owner[v], f);
        expected_vf += expect;
        ASSERT_EQ(std::binary_search(vf.begin(), vf.end(), VertexFacePair{v, f}), expect) << "v " << v << " f " << f;
      }
    for (Index a = 0; a < mesh.num_edges(); ++a)
      for (Index b = a + 1; b < mesh.num_edges(); ++b) {
        if (shares_vertex(mesh.edge(a), mesh.edge(b))) continue;
        Index oa = own.edge_owner[a], ob = own.edge_owner[b];
        bool expect = mesh.faces_adjacent(oa, ob) || is_candidate(oa, ob);
        expected_ee += expect;
        ASSERT_EQ(std::binary_search(ee.begin(), ee.end(), EdgeEdgePair{a, b}), expect) << "a " << a << " b " << b;
      }
    EXPECT_EQ(vf.size(), expected_vf);
    EXPECT_EQ(ee.size(), expected_ee);

    expect_every_contact_gathered(pipeline, gathered, x0, x1);
  }
}

TEST(Representatives, FirstFreeTestsEveryFeaturePairOnceThroughItsFirstNonAdjacentFacePair) {
  MeshData g = test::grid(8, 8);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  CcdPipeline pipeline(mesh, single_cloth_body(mesh), default_strategies(18, {NarrowMode::batched, RepresentativeRule::first_free, {}}));
  const Gathered gathered = gather_one_step(pipeline, g, 17);
  const auto& vf = gathered.vf;
  const auto& ee = gathered.ee;
  auto is_candidate = [&](Index f, Index g2) { return gathered.is_candidate(f, g2); };
  std::size_t orphans_vf = 0, orphans_ee = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v)
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      if (contains_vertex(mesh.face(f), v)) continue;
      const Index rep = first_free_vf(mesh, v, f);
      orphans_vf += rep < 0;
      const bool expect = rep < 0 || is_candidate(rep, f);
      ASSERT_EQ(std::binary_search(vf.begin(), vf.end(), VertexFacePair{v, f}), expect) << "v " << v << " f " << f;
    }
  for (Index a = 0; a < mesh.num_edges(); ++a)
    for (Index b = a + 1; b < mesh.num_edges(); ++b) {
      if (shares_vertex(mesh.edge(a), mesh.edge(b))) continue;
      const auto rep = first_free_ee(mesh, a, b);
      orphans_ee += rep.first < 0;
      const bool expect = rep.first < 0 || is_candidate(rep.first, rep.second);
      ASSERT_EQ(std::binary_search(ee.begin(), ee.end(), EdgeEdgePair{a, b}), expect) << "a " << a << " b " << b;
    }
  EXPECT_EQ(pipeline.orphans().vf.size(), orphans_vf);
  EXPECT_EQ(pipeline.orphans().ee.size(), orphans_ee);
  // Far fewer orphans than the fixed rule's (a grid: only around the corners and borders).
  const OrphanSet fixed = build_orphan_set(mesh, assign_owners(mesh), [](Index) { return true; });
  EXPECT_LT(orphans_vf + orphans_ee, (fixed.vf.size() + fixed.ee.size()) / 4);
}

TEST(Representatives, CarriedOrphansAreTestedOnceThroughTheirFirstNonAdjacentFacePair) {
  // The fixed rule with the candidates carrying the orphans: a pair of non-adjacent owners is tested through
  // its owners' candidate, an orphan through the first non-adjacent face pair of its features (first_free's
  // choice), and only an orphan with none through the orphan loop.
  MeshData g = test::grid(8, 8);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  CcdPipeline pipeline(mesh, single_cloth_body(mesh),
                       default_strategies(18, {NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::on}}));
  Positions x0, x1;
  const Gathered gathered = gather_one_step(pipeline, g, 23, &x0, &x1);
  const Ownership& own = pipeline.representatives().owners();
  const auto was_gathered = [&](const auto& pairs, const auto& pair) { return std::binary_search(pairs.begin(), pairs.end(), pair); };
  std::size_t carried = 0, uncarried = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v)
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      if (contains_vertex(mesh.face(f), v)) continue;
      bool expect = gathered.is_candidate(own.vertex_owner[v], f);
      if (mesh.faces_adjacent(own.vertex_owner[v], f)) {
        const Index rep = first_free_vf(mesh, v, f);
        expect = rep < 0 || gathered.is_candidate(rep, f);
        (rep < 0 ? uncarried : carried) += 1;
      }
      ASSERT_EQ(was_gathered(gathered.vf, VertexFacePair{v, f}), expect) << "v " << v << " f " << f;
    }
  for (Index a = 0; a < mesh.num_edges(); ++a)
    for (Index b = a + 1; b < mesh.num_edges(); ++b) {
      if (shares_vertex(mesh.edge(a), mesh.edge(b))) continue;
      const Index oa = own.edge_owner[a], ob = own.edge_owner[b];
      bool expect = gathered.is_candidate(oa, ob);
      if (mesh.faces_adjacent(oa, ob)) {
        const auto rep = first_free_ee(mesh, a, b);
        expect = rep.first < 0 || gathered.is_candidate(rep.first, rep.second);
        (rep.first < 0 ? uncarried : carried) += 1;
      }
      ASSERT_EQ(was_gathered(gathered.ee, EdgeEdgePair{a, b}), expect) << "a " << a << " b " << b;
    }
  const Representatives& reps = pipeline.representatives();
  EXPECT_EQ(reps.orphans().vf.size() + reps.orphans().ee.size(), carried + uncarried);
  EXPECT_EQ(reps.uncarried_orphans().vf.size() + reps.uncarried_orphans().ee.size(), uncarried);
  EXPECT_GT(carried, 4 * uncarried);  // the uncarried lie at the borders and corners
  expect_every_contact_gathered(pipeline, gathered, x0, x1);
}

TEST(OrphanSet, CoversExactlyThePairsOfAdjacentOwners) {
  MeshData g = test::grid(5, 5);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  Ownership own = assign_owners(mesh);
  OrphanSet orphans = build_orphan_set(mesh, own, [](Index) { return true; });
  std::set<VertexFacePair> vf(orphans.vf.begin(), orphans.vf.end());
  std::set<EdgeEdgePair> ee(orphans.ee.begin(), orphans.ee.end());
  EXPECT_EQ(vf.size(), orphans.vf.size());
  EXPECT_EQ(ee.size(), orphans.ee.size());
  for (Index v = 0; v < mesh.num_vertices(); ++v)
    for (Index f = 0; f < mesh.num_faces(); ++f)
      if (!contains_vertex(mesh.face(f), v)) {
        EXPECT_EQ(vf.count({v, f}) > 0, mesh.faces_adjacent(own.vertex_owner[v], f));
      }
  // No self-collision: no orphans.
  OrphanSet none = build_orphan_set(mesh, own, [](Index) { return false; });
  EXPECT_TRUE(none.vf.empty() && none.ee.empty());
}

}  // namespace
}  // namespace ccdlab
