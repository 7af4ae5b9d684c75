// The proximity query (framework/pipeline/proximity/proximity_query.hpp) against brute force: every non-adjacent VF and EE
// pair of the mesh decided by the same exact test (no BVH, no ownership, no culling), and an independent double
// reference (Ericson's closest points) away from d̂; for every scheduler, thread count, K and BVH width; one hash.
#include <gtest/gtest.h>

#include <random>

#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/proximity/proximity_query.hpp"
#include "strategies/registry.hpp"
#include "support/registries.hpp"
#include "support/error_of.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

PipelineStrategies strategies(const std::string& scheduler, int threads, int k, int width) {
  PipelineStrategies s;
  s.k = k, s.width = width, s.threads = threads;
  s.builder = builder_registry().make({"median", builder_registry().find("median")->defaults()});
  s.scheduler = scheduler_registry().make({scheduler, scheduler_registry().find(scheduler)->defaults()});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});  // replaced by the query
  return s;
}

using Key = std::tuple<ContactKind, Index, Index>;
std::vector<Key> keys(const Contacts& cs) {
  std::vector<Key> k;
  for (const Contact& c : cs) k.push_back(c.key());
  return k;
}

/// Every pair the brute force finds, and an independent check of it: pairs whose double distance is below
/// d̂(1 − 1e-9) are in it, pairs above d̂(1 + 1e-9) are not.
Contacts reference(const TriMesh& mesh, const CollisionRules& rules, const Positions& x, double dhat) {
  const StaticDistanceTester tester(dhat);
  Contacts all = brute_force_contacts(mesh, rules, x, x, tester);
  std::set<Key> found;
  for (const Contact& c : all) found.insert(c.key());
  const auto check = [&](ContactKind kind, Index a, Index b, double d) {
    if (d < dhat * (1 - 1e-9)) { EXPECT_TRUE(found.count({kind, a, b})) << "missed at distance " << d; }
    if (d > dhat * (1 + 1e-9)) { EXPECT_FALSE(found.count({kind, a, b})) << "reported at distance " << d; }
  };
  for (Index v = 0; v < mesh.num_vertices(); ++v)
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      const Face& t = mesh.faces()[f];
      if (t[0] == v || t[1] == v || t[2] == v) continue;
      if (!rules.bodies_interact(rules.body_of_vertex(v), rules.body_of_face(f))) continue;
      check(ContactKind::vf, v, f, closest_vertex_face(x[v], x[t[0]], x[t[1]], x[t[2]]).distance);
    }
  for (Index a = 0; a < mesh.num_edges(); ++a)
    for (Index b = a + 1; b < mesh.num_edges(); ++b) {
      const Edge &ea = mesh.edges()[a], &eb = mesh.edges()[b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
      if (!rules.bodies_interact(rules.body_of_vertex(ea[0]), rules.body_of_vertex(eb[0]))) continue;
      check(ContactKind::ee, a, b, closest_edge_edge(x[ea[0]], x[ea[1]], x[eb[0]], x[eb[1]]).distance);
    }
  return all;
}

TEST(ProximityQuery, FindsExactlyTheBruteForcePairsForEverySchedule) {
  MeshData g = test::grid(10, 8);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(3);
  const Positions x = test::crumple(g.positions, rng, 0.02);
  for (const double dhat : {0.02, 0.08}) {
    const Contacts expected = reference(mesh, CollisionRules(mesh, single_cloth_body(mesh)), x, dhat);
    ASSERT_GT(expected.size(), 30u) << "the crumpled sheet must have near pairs, or the test proves nothing";
    std::uint64_t hash = 0;
    for (const std::string& scheduler : test::bvtt_schedulers())
      for (const int threads : {1, 2})
        for (const auto& [k, width] : {std::pair{6, 2}, std::pair{18, 4}, std::pair{26, 4}}) {
          const std::string label = fmt::format("dhat {} {} x{} k={} width={}", dhat, scheduler, threads, k, width);
          ProximityQuery q(mesh, single_cloth_body(mesh), strategies(scheduler, threads, k, width), dhat);
          for (int repeat = 0; repeat < 2; ++repeat) {  // built, then refit
            const ProximityResult r = q.query(x);
            ASSERT_EQ(r.pairs.size(), expected.size()) << label;
            for (std::size_t i = 0; i < r.pairs.size(); ++i) {
              const ProximityPair& p = r.pairs[i];
              EXPECT_EQ(p.kind, expected[i].kind) << label;
              EXPECT_EQ(p.vertices, expected[i].vertices) << label;
              EXPECT_LT(p.distance, dhat * (1 + 1e-9)) << label;
            }
            if (hash == 0) hash = r.hash;
            EXPECT_EQ(r.hash, hash) << label;
          }
        }
  }
}

TEST(ProximityQuery, ClothAgainstAnObstacleAndAfterMotion) {
  // A cloth (no self-collision) hovering over a wavy obstacle; then moved: the refit hierarchy follows.
  MeshData cloth = test::grid(7, 7), obstacle = test::grid(6, 5);
  for (Vec3& p : obstacle.positions) p = Vec3(p.x() * 1.2 - 0.1, p.y() * 1.2 - 0.1, -0.03 + 0.02 * std::sin(7 * p.x()));
  MeshData both = test::concat(cloth, obstacle);
  TriMesh mesh(Index(both.positions.size()), both.faces);
  const Index nv = Index(cloth.positions.size()), nf = Index(cloth.faces.size());
  const std::vector<Body> bodies{{"cloth", BodyKind::cloth, false, 0, nv, 0, nf},
                                 {"obstacle", BodyKind::obstacle, false, nv, mesh.num_vertices(), nf, mesh.num_faces()}};
  const CollisionRules rules(mesh, bodies);
  ProximityQuery q(mesh, bodies, strategies("phc", 2, 18, 4), 0.03);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int frame = 0; frame < 3; ++frame) {
    Positions x = both.positions;
    for (Index v = 0; v < nv; ++v) x[v] += Vec3(0.01 * u(rng), 0.01 * u(rng), 0.01 * frame + 0.01 * u(rng));
    const ProximityResult r = q.query(x);
    const Contacts expected = reference(mesh, rules, x, 0.03);
    EXPECT_EQ(keys(r.step.contacts).size(), 0u) << "the contacts are moved into the pairs";
    ASSERT_EQ(r.pairs.size(), expected.size()) << "frame " << frame;
    for (std::size_t i = 0; i < r.pairs.size(); ++i) EXPECT_EQ(r.pairs[i].vertices, expected[i].vertices);
    if (frame == 0) { EXPECT_GT(r.pairs.size(), 10u); }
    for (const ProximityPair& p : r.pairs) {  // every pair joins the two bodies
      const bool a_cloth = p.vertices[0] < nv, b_cloth = p.vertices[p.kind == ContactKind::vf ? 1 : 2] < nv;
      EXPECT_NE(a_cloth, b_cloth);
    }
  }
}

TEST(ProximityQuery, RefusesADhatLargerThanTheScene) {
  // As a CCD thickness in the wrong unit: the work estimate refuses before the quadratic traversal.
  MeshData g = test::grid(50, 50);  // 5,000 faces: every pair is ~2,500 per face
  TriMesh mesh(Index(g.positions.size()), g.faces);
  ProximityQuery q(mesh, single_cloth_body(mesh), strategies("sequential", 1, 18, 4), 10.0);
  const std::string message = test::error_of([&] { (void)q.query(g.positions); });
  EXPECT_NE(message.find("dhat 10 is"), std::string::npos) << message;
}

}  // namespace
}  // namespace ccdlab
