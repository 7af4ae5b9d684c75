// Stage 0 (triangle_filter.hpp): every SIMD target agrees with the plain version, a culled candidate never has a
// feature pair the tester reports (also where the float copy's rounding is as large as the triangles), the
// reach is honoured to within its rounding, faces that pass each other are kept while faces apart at both ends
// are dropped, and the pipeline's contacts do not change when stage 0 runs
// (test_narrow_phase.cpp compares every mode with brute force).
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <array>
#include <random>
#include <vector>

#include "framework/narrow/triangle_filter.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "strategies/testers/float_tester.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// Two random triangles per candidate in a thin slab, moving: many near contacts, many clear separations.
/// Every 9th pair shares a vertex; every 13th has a degenerate (collinear) face.
struct RandomPairs {
  Positions x0, x1;
  std::vector<Face> faces;
  std::vector<FacePair> candidates;
};
/// `spread` > 0 places each pair at a random point of a cube that wide, so that far from the frames' centre the
/// float copy errs by as much as the smallest triangles measure.
RandomPairs random_pairs(int n, unsigned seed, double motion, double spread = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), scale(-4, 2);
  RandomPairs r;
  for (int i = 0; i < n; ++i) {
    const double s = std::pow(10.0, scale(rng));
    const Vec3 at = spread * Vec3(u(rng), u(rng), u(rng));
    const Index base = Index(r.x0.size());
    for (int k = 0; k < 6; ++k) {
      const Vec3 p = at + s * Vec3(u(rng), u(rng), 0.2 * u(rng));
      r.x0.push_back(p);
      r.x1.push_back(p + motion * s * Vec3(u(rng), u(rng), u(rng)));
    }
    if (i % 13 == 0) r.x0[base + 2] = 0.5 * (r.x0[base] + r.x0[base + 1]), r.x1[base + 2] = 0.5 * (r.x1[base] + r.x1[base + 1]);
    Face f{base, base + 1, base + 2}, g{base + 3, base + 4, base + 5};
    if (i % 9 == 0) g[1] = f[2];
    r.faces.push_back(f);
    r.faces.push_back(g);
    r.candidates.push_back({2 * i, 2 * i + 1});
  }
  return r;
}

const std::vector<Face> kTwoFaces = {{0, 1, 2}, {3, 4, 5}};

FloatFrames float_frames(const RandomPairs& r) {
  FloatFrames frames;
  frames.update(r.x0.data(), r.x1.data(), r.x0.size(), r.faces);
  return frames;
}

TEST(TriangleFilter, EverySimdTargetAgreesWithThePlainVersion) {
  for (double motion : {0.0, 0.3}) {
    const RandomPairs r = random_pairs(4099, 5, motion);  // not a multiple of any vector or block size
    const FloatFrames frames = float_frames(r);
    for (CullReach reach : {CullReach{0, 0}, CullReach{0, 2e-9}, CullReach{1e-3, 2e-9}}) {
      std::vector<std::uint8_t> expect(r.candidates.size());
      std::size_t culled = 0;
      for (std::size_t i = 0; i < expect.size(); ++i) {
        const FacePair& p = r.candidates[i];
        culled += !(expect[i] = triangle_pair_keeps(r.faces[p.a], r.faces[p.b], frames, reach));
      }
      EXPECT_GT(culled, expect.size() / 10);  // the comparison means something: both answers are common
      EXPECT_LT(culled, expect.size() * 9 / 10);
      const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
      ASSERT_FALSE(targets.empty());
      std::vector<std::size_t> fine;  // what x, y, z left for the second pass: the same on every target
      for (std::int64_t t : targets) {
        hwy::SetSupportedTargetsForTest(t);
        std::vector<std::uint8_t> keep(expect.size(), 7);
        fine.push_back(triangle_filter(r.candidates, r.faces.data(), frames, reach, keep.data()));
        EXPECT_EQ(keep, expect) << hwy::TargetName(t) << " motion " << motion << " reach " << reach.abs;
        EXPECT_EQ(fine.back(), fine.front()) << hwy::TargetName(t);
        // Without the box pass (steps that tested end boxes): every candidate to the second pass, which keeps
        // all that both passes keep and culls only by the other axes — the same answers on every target.
        std::vector<std::uint8_t> keep_all(expect.size(), 7);
        EXPECT_EQ(triangle_filter(r.candidates, r.faces.data(), frames, reach, keep_all.data(), false), expect.size());
        std::size_t more = 0;
        for (std::size_t i = 0; i < expect.size(); ++i) {
          EXPECT_TRUE(keep_all[i] == 0 || keep_all[i] == 1);
          EXPECT_GE(keep_all[i], keep[i]) << i;
          more += keep_all[i] > keep[i];
        }
        EXPECT_LT(more, culled) << hwy::TargetName(t) << ": the other axes culled nothing";
      }
      // Every kept candidate went through both passes; x, y and z alone drop some of the culled ones.
      EXPECT_GE(fine.front(), expect.size() - culled);
      EXPECT_LT(fine.front(), expect.size());
      hwy::SetSupportedTargetsForTest(0);
    }
  }
}

/// Over random pairs: every candidate with a pair the float tester reports is kept. Returns {hits, culled}.
std::pair<int, int> check_never_drops_a_hit(double eta, double spread) {
  FloatTester tester(FloatTester::Params{eta});
  const CullReach reach = *tester.cull_reach();
  const RandomPairs r = random_pairs(20000, 17, 0.1, spread);
  const FloatFrames frames = float_frames(r);
  int hits = 0, culled = 0;
  {
    for (const FacePair& p : r.candidates) {
      const Face &f = r.faces[p.a], &g = r.faces[p.b];
      bool hit = false;
      for (int pass = 0; pass < 2; ++pass) {  // the VF pairs both ways
        const Face &face = pass == 0 ? f : g, &other = pass == 0 ? g : f;
        for (Index v : other)
          hit |= tester.vertex_face({r.x0[v], r.x0[face[0]], r.x0[face[1]], r.x0[face[2]], r.x1[v], r.x1[face[0]],
                                     r.x1[face[1]], r.x1[face[2]]}).hit;
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const Index a0 = f[i], a1 = f[(i + 1) % 3], b0 = g[j], b1 = g[(j + 1) % 3];
          hit |= tester.edge_edge({r.x0[a0], r.x0[a1], r.x0[b0], r.x0[b1], r.x1[a0], r.x1[a1], r.x1[b0], r.x1[b1]}).hit;
        }
      const bool keep = triangle_pair_keeps(f, g, frames, reach);
      hits += hit;
      culled += !keep;
      if (hit) {
        EXPECT_TRUE(keep) << "eta " << eta << " spread " << spread << " candidate " << p.a / 2;
      }
    }
  }
  return {hits, culled};
}

TEST(TriangleFilter, NeverDropsACandidateWithAPairTheFloatTesterReports) {
  for (double eta : {0.0, 0.02}) {
    const auto [hits, culled] = check_never_drops_a_hit(eta, 0);
    EXPECT_GT(hits, 1000);
    EXPECT_GT(culled, 2000);
  }
}

TEST(TriangleFilter, NeverDropsAHitWhereTheFloatCopyErrsAsMuchAsTheTrianglesMeasure) {
  // Pairs spread over a cube of 2·10⁴: the float copy errs by ~10⁻³ there, the smallest pairs measure 10⁻⁴.
  for (double eta : {0.0, 0.02}) {
    const auto [hits, culled] = check_never_drops_a_hit(eta, 1e4);
    EXPECT_GT(hits, 1000);
    EXPECT_GT(culled, 2000);
  }
}

TEST(TriangleFilter, KeepsAPairWithinTheReachAndDropsOneJustBeyondIt) {
  // Two parallel horizontal triangles of size 1, still, at distance d: kept at d = η(1 − 10⁻⁶), dropped at
  // η(1 + 0.05) — float rounding (16u·L̄ ≈ 2·10⁻⁶ here) is the margin. The same far from the origin: the float
  // copy is taken about the frames' centre, so the offset costs no precision.
  const double eta = 1e-4;
  const CullReach reach{eta, 0};
  for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(1e7, -3e6, 5e5)})
    for (double factor : {1 - 1e-6, 1 + 0.05}) {
      const double d = eta * factor;
      Positions x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, d}, {1.2, 0.2, d}, {0.2, 1.2, d}};
      for (Vec3& p : x) p += offset;
      FloatFrames frames;
      frames.update(x.data(), x.data(), x.size(), kTwoFaces);
      const bool keep = triangle_pair_keeps({0, 1, 2}, {3, 4, 5}, frames, reach);
      EXPECT_EQ(keep, factor < 1) << "d = η·" << factor << ", offset " << offset.transpose();
    }
}

TEST(TriangleFilter, SeparatesAtBothEndsWhereTheSweptVolumesOverlap) {
  // f in the plane y = 0 (an edge along x at z = 0, its apex below), g in the plane x = 0 (an edge along y at
  // z = d, its apex above): each face's plane cuts the other, so neither normal separates them; the z axis does
  // when d > 0, at both ends of the step. Both move by 3 along x, so their swept boxes overlap whatever d is.
  // At d < 0 they intersect throughout. And g moving from d to −d passes through f: never dropped.
  const Positions x0 = {{-1, 0, 0}, {1, 0, 0}, {0, 0, -1}, {0, -1, 0}, {0, 1, 0}, {0, 0, 1}};
  const auto moved = [&](double d_start, double d_end) {
    Positions a = x0, b = x0;
    for (int k = 3; k < 6; ++k) a[k].z() += d_start, b[k].z() += d_end;
    for (Vec3& p : b) p.x() += 3;
    FloatFrames frames;
    frames.update(a.data(), b.data(), a.size(), kTwoFaces);
    return triangle_pair_keeps({0, 1, 2}, {3, 4, 5}, frames, CullReach{0, 2e-9});
  };
  EXPECT_FALSE(moved(0.01, 0.01));
  EXPECT_TRUE(moved(-0.01, -0.01));
  EXPECT_TRUE(moved(0.5, -0.5));
}

PipelineStrategies float_strategies(NarrowMode mode) {
  PipelineStrategies s;
  s.k = 18;
  s.threads = 1;
  s.narrow = {mode, RepresentativeRule::fixed, {}};
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({"sequential", scheduler_registry().find("sequential")->defaults()});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  return s;
}

TEST(TriangleFilter, RunsInThePipelineAndLeavesItsContactsAlone) {
  MeshData g = test::grid(16, 16);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(21);
  Positions x0 = test::crumple(g.positions, rng, 0.02), x1 = x0;
  std::uniform_real_distribution<double> u(-1, 1);
  for (Vec3& p : x1) p += 0.002 * Vec3(u(rng), u(rng), u(rng));
  CcdPipeline batched(mesh, single_cloth_body(mesh), float_strategies(NarrowMode::batched));
  CcdPipeline scalar(mesh, single_cloth_body(mesh), float_strategies(NarrowMode::scalar));
  const StepResult b = batched.step(x0, x1), s = scalar.step(x0, x1);
  EXPECT_GT(b.counters.triangle_culled, b.counters.candidate_pairs / 10);
  EXPECT_EQ(s.counters.triangle_culled, 0u);  // the scalar mode has no stage 0
  EXPECT_GT(b.contacts.size(), 5u);
  EXPECT_EQ(contact_set_hash(b.contacts), contact_set_hash(s.contacts));
}

}  // namespace
}  // namespace ccdlab
