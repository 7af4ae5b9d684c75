// The proximity query on every real frame of ../shared/data/meshes (skipped where absent), at two d̂ (10⁻³ and
// 5·10⁻⁴ of the frame's bounding-box diagonal), against an independent reference (sweep_proximity: a sweep over x
// of the features' axis-aligned boxes grown by d̂, no BVH, no ownership, no culling stage, every pair whose boxes
// meet decided by the exact test), its pairs checked by Ericson's closest points in double. The reference's hash for
// every scheduler and thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <set>

#include "framework/mesh/mesh_io.hpp"
#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/proximity/proximity_query.hpp"
#include "framework/pipeline/proximity/sweep_proximity.hpp"
#include "framework/pipeline/work_estimate.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

struct Frame {
  const char* scene;
  const char* file;
};

using Key = std::tuple<ContactKind, std::array<Index, 4>>;

/// The reference's pairs (framework/pipeline/brute_force.hpp: a sweep over boxes, the exact test), checked by
/// Ericson's closest points in double away from d̂: none of them farther than d̂.
std::set<Key> reference(const TriMesh& mesh, const Positions& x, double dhat, std::uint64_t& hash) {
  const Contacts pairs = sweep_proximity(mesh, CollisionRules(mesh, single_cloth_body(mesh)), x, dhat);
  hash = contact_set_hash(pairs);
  std::set<Key> out;
  for (const Contact& c : pairs) {
    const auto& v = c.vertices;
    const double d = c.kind == ContactKind::vf ? closest_vertex_face(x[v[0]], x[v[1]], x[v[2]], x[v[3]]).distance
                                               : closest_edge_edge(x[v[0]], x[v[1]], x[v[2]], x[v[3]]).distance;
    EXPECT_LT(d, dhat * (1 + 1e-9));
    out.insert({c.kind, v});
  }
  return out;
}

PipelineStrategies strategies(const char* scheduler, int threads) {
  PipelineStrategies s;
  s.threads = threads;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({scheduler, scheduler_registry().find(scheduler)->defaults()});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  return s;
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define CCDLAB_SANITIZED 1
#endif
#endif
/// Under a sanitizer (10× slower) only the smallest frames run: the code paths are the same on all six.
#ifdef CCDLAB_SANITIZED
constexpr Index kLargestFrame = 30000;
#else
constexpr Index kLargestFrame = std::numeric_limits<Index>::max();
#endif

class RealProximity : public ::testing::TestWithParam<Frame> {};

TEST_P(RealProximity, FindsExactlyTheReferencePairsForEverySchedule) {
  const std::string root = test::shared_data();
  const std::string path = root + "/meshes/" + GetParam().scene + "/" + GetParam().file;
  if (root.empty() || !std::filesystem::exists(path)) GTEST_SKIP() << path << " not found: real-data test skipped";
  const MeshData m = read_mesh(path);
  const TriMesh mesh(m.positions.size(), m.faces);
  if (mesh.num_faces() > kLargestFrame) GTEST_SKIP() << "under a sanitizer only frames up to " << kLargestFrame << " triangles";
  const double diagonal = bounding_box_diagonal(m.positions);
  // Every schedule on the smallest frame; sequential × 1 and phc × 2 on the others.
  const bool small = mesh.num_faces() < 30000;
  std::vector<std::pair<const char*, int>> schedules{{"sequential", 1}, {"phc", 2}};
  if (small) schedules.insert(schedules.end(), {{"front", 2}, {"static", 2}, {"phc", 1}});
  for (const double relative : {1e-3, 5e-4}) {
    const double dhat = relative * diagonal;
    std::uint64_t expected_hash = 0;
    const std::set<Key> expected = reference(mesh, m.positions, dhat, expected_hash);
    EXPECT_GT(expected.size(), 1000u) << "frames this dense have many near pairs at " << relative << " of the diagonal";
    for (const auto& [scheduler, threads] : schedules) {
      ProximityQuery q(mesh, single_cloth_body(mesh), strategies(scheduler, threads), dhat);
      const ProximityResult r = q.query(m.positions);
      std::set<Key> got;
      for (const ProximityPair& p : r.pairs) got.insert({p.kind, p.vertices});
      EXPECT_EQ(got.size(), r.pairs.size()) << "a pair reported twice";
      EXPECT_TRUE(got == expected) << scheduler << " x" << threads << " at " << relative << ": " << got.size()
                                   << " pairs, the reference " << expected.size();
      EXPECT_EQ(r.hash, expected_hash) << scheduler << " x" << threads;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(SharedFrames, RealProximity,
                         ::testing::Values(Frame{"cloth-funnel", "227.ply"}, Frame{"cloth-funnel", "228.ply"},
                                           Frame{"rod-twist", "3036.ply"}, Frame{"rod-twist", "3037.ply"},
                                           Frame{"n-body-simulation", "balls16_18.ply"},
                                           Frame{"n-body-simulation", "balls16_19.ply"}),
                         [](const auto& info) {
                           std::string name = std::string(info.param.scene) + "_" + info.param.file;
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
}  // namespace ccdlab
