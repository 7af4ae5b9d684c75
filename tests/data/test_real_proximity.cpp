// The proximity query on every real frame of ../shared/data/meshes (skipped where absent), at two d̂ (10⁻³ and
// 5·10⁻⁴ of the frame's bounding-box diagonal), against an independent reference: a sweep over x of the
// features' axis-aligned boxes grown by d̂ (no BVH, no ownership, no culling stage), every non-adjacent vertex–face
// and edge–edge pair whose boxes meet decided by the exact test — and, away from d̂, by Ericson's closest points
// in double. One hash for every scheduler and thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <set>

#include "framework/mesh/mesh_io.hpp"
#include "framework/pipeline/proximity_query.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace {

struct Frame {
  const char* scene;
  const char* file;
};

using Key = std::tuple<ContactKind, std::array<Index, 4>>;

struct Box {
  Vec3 lo, hi;
  Index id;
};

/// Boxes of each face (or edge) of `corners` points, grown by `r`, sorted by lo.x.
template <class Feature>
std::vector<Box> boxes(const std::vector<Feature>& features, const Positions& x, double r) {
  std::vector<Box> out;
  out.reserve(features.size());
  for (std::size_t i = 0; i < features.size(); ++i) {
    Vec3 lo = x[features[i][0]], hi = lo;
    for (const Index v : features[i]) lo = lo.cwiseMin(x[v]), hi = hi.cwiseMax(x[v]);
    out.push_back({lo.array() - r, hi.array() + r, Index(i)});
  }
  std::sort(out.begin(), out.end(), [](const Box& a, const Box& b) { return a.lo.x() < b.lo.x(); });
  return out;
}

bool overlap_yz(const Vec3& lo, const Vec3& hi, const Box& b) {
  return lo.y() <= b.hi.y() && b.lo.y() <= hi.y() && lo.z() <= b.hi.z() && b.lo.z() <= hi.z();
}

/// Every pair closer than dhat, found by the sweep and decided by the exact test; pairs clearly nearer or farther
/// than d̂ in double agree with it.
std::set<Key> reference(const TriMesh& mesh, const Positions& x, double dhat) {
  const double r = dhat * (1 + 1e-6);  // boxes a little larger than d̂: a box test never drops a pair at d̂
  std::set<Key> out;
  const auto decide = [&](ContactKind kind, const std::array<Index, 4>& v) {
    const bool vf = kind == ContactKind::vf;
    const DistanceVerdict d = vf ? vertex_face_closer(x[v[0]], x[v[1]], x[v[2]], x[v[3]], dhat)
                                 : edge_edge_closer(x[v[0]], x[v[1]], x[v[2]], x[v[3]], dhat);
    const double e = vf ? closest_vertex_face(x[v[0]], x[v[1]], x[v[2]], x[v[3]]).distance
                        : closest_edge_edge(x[v[0]], x[v[1]], x[v[2]], x[v[3]]).distance;
    if (e < dhat * (1 - 1e-9)) { EXPECT_TRUE(d.closer) << "double distance " << e; }
    if (e > dhat * (1 + 1e-9)) { EXPECT_FALSE(d.closer) << "double distance " << e; }
    if (d.closer) out.insert({kind, v});
  };
  // Vertices against faces: the vertices sorted by x, each face's box scanning its x range.
  std::vector<Index> by_x(mesh.num_vertices());
  for (Index v = 0; v < mesh.num_vertices(); ++v) by_x[v] = v;
  std::sort(by_x.begin(), by_x.end(), [&](Index a, Index b) { return x[a].x() < x[b].x(); });
  for (const Box& f : boxes(mesh.faces(), x, r)) {
    const Face& t = mesh.faces()[f.id];
    auto it = std::lower_bound(by_x.begin(), by_x.end(), f.lo.x(), [&](Index v, double lo) { return x[v].x() < lo; });
    for (; it != by_x.end() && x[*it].x() <= f.hi.x(); ++it) {
      const Index v = *it;
      if (v == t[0] || v == t[1] || v == t[2] || !overlap_yz(x[v], x[v], f)) continue;
      decide(ContactKind::vf, {v, t[0], t[1], t[2]});
    }
  }
  // Edges against edges: sweep and prune over x.
  const std::vector<Box> e = boxes(mesh.edges(), x, r / 2);
  for (std::size_t i = 0; i < e.size(); ++i)
    for (std::size_t j = i + 1; j < e.size() && e[j].lo.x() <= e[i].hi.x(); ++j) {
      if (!overlap_yz(e[i].lo, e[i].hi, e[j])) continue;
      const Index a = std::min(e[i].id, e[j].id), b = std::max(e[i].id, e[j].id);
      const Edge &ea = mesh.edges()[a], &eb = mesh.edges()[b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
      decide(ContactKind::ee, {ea[0], ea[1], eb[0], eb[1]});
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

class RealProximity : public ::testing::TestWithParam<Frame> {};

TEST_P(RealProximity, FindsExactlyTheReferencePairsForEverySchedule) {
  const std::string root = test::shared_data();
  const std::string path = root + "/meshes/" + GetParam().scene + "/" + GetParam().file;
  if (root.empty() || !std::filesystem::exists(path)) GTEST_SKIP() << path << " not found: real-data test skipped";
  const MeshData m = read_mesh(path);
  const TriMesh mesh(m.positions.size(), m.faces);
  Vec3 lo = m.positions[0], hi = lo;
  for (const Vec3& p : m.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double diagonal = (hi - lo).norm();
  // Every schedule on the smallest frame; sequential × 1 and phc × 2 on the others.
  const bool small = mesh.num_faces() < 30000;
  std::vector<std::pair<const char*, int>> schedules{{"sequential", 1}, {"phc", 2}};
  if (small) schedules.insert(schedules.end(), {{"front", 2}, {"static", 2}, {"phc", 1}});
  for (const double relative : {1e-3, 5e-4}) {
    const double dhat = relative * diagonal;
    const std::set<Key> expected = reference(mesh, m.positions, dhat);
    EXPECT_GT(expected.size(), 1000u) << "frames this dense have many near pairs at " << relative << " of the diagonal";
    std::optional<std::uint64_t> hash;
    for (const auto& [scheduler, threads] : schedules) {
      ProximityQuery q(mesh, single_cloth_body(mesh), strategies(scheduler, threads), dhat);
      const ProximityResult r = q.query(m.positions);
      std::set<Key> got;
      for (const ProximityPair& p : r.pairs) got.insert({p.kind, p.vertices});
      EXPECT_EQ(got.size(), r.pairs.size()) << "a pair reported twice";
      EXPECT_TRUE(got == expected) << scheduler << " x" << threads << " at " << relative << ": " << got.size()
                                   << " pairs, the reference " << expected.size();
      if (!hash) hash = r.hash;
      EXPECT_EQ(r.hash, *hash) << scheduler << " x" << threads;
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
