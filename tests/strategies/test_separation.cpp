// `conservative` with thickness η > 0 (separation_search.hpp) on families whose closest approach is known in
// closed form: a vertex sinking onto a face, a vertex passing an edge of a face, an edge passing the end of
// another edge — each coming within η·(1 − 10⁻⁶) (must be reported, never late) or staying at η·(1 + 10⁻⁶)
// (must not be, once δ is below the gap), rotated, scaled over 10⁻³…10³ and moved far from the origin.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "framework/geometry/distance.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "strategies/testers/conservative_tester.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// A random rotation, scale and translation applied to every point of a query.
struct Placement {
  Eigen::Matrix3d R;
  double scale;
  Vec3 shift;
  [[nodiscard]] Vec3 operator()(const Vec3& p) const { return R * (scale * p) + shift; }
};

Placement random_placement(std::mt19937& rng) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> e(-3, 3), s(-1, 1);
  const Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  const double scale = std::pow(10.0, e(rng));
  return {q.normalized().toRotationMatrix(), scale, scale * 100 * Vec3(s(rng), s(rng), s(rng))};
}

/// The families in the unit frame come within η·(1 ± 10⁻⁶), η = 10⁻³ (scaled with the placement).
constexpr double kEta = 1e-3, kGap = 1e-6;

/// A query, its minimum distance (in the unit frame) and the first time the distance reaches η.
struct Family {
  const char* name;
  bool vf;
  VertexFaceQuery qv;
  EdgeEdgeQuery qe;
  double toi;  ///< the first time the distance reaches η (when it does)
};

/// Vertex sinking onto the face z = 0 above an interior point, the whole pair drifting: distance z(t), from a to
/// `closest` at t = 1; the face is the unit right triangle.
Family sinking(double closest, std::mt19937& rng, const Placement& P) {
  std::uniform_real_distribution<double> w(0.15, 0.35), up(2, 20), drift(-2, 2);
  const Vec3 foot(w(rng), w(rng), 0), d(drift(rng), drift(rng), drift(rng));
  const Vec3 f0(0, 0, 0), f1(1, 0, 0), f2(0, 1, 0), z(0, 0, 1);
  const double a = closest * up(rng);
  return {"sinking", true,
          {P(foot + a * z), P(f0), P(f1), P(f2), P(foot + closest * z + d), P(f0 + d), P(f1 + d), P(f2 + d)}, {},
          (a - kEta) / (a - closest)};
}

/// Vertex passing the edge f1 f2 outside the face, moving along z: distance √(c² + s²(t − tc)²), the closest
/// `closest` at tc inside the step.
Family passing(double closest, std::mt19937& rng, const Placement& P) {
  std::uniform_real_distribution<double> tc(0.2, 0.8), speed(0.5, 5);
  const double t_c = tc(rng), s = speed(rng);
  const Vec3 f0(0, 0, 0), f1(1, 0, 0), f2(0, 1, 0), out = Vec3(1, 1, 0).normalized(), z(0, 0, 1);
  const Vec3 at_tc = Vec3(0.5, 0.5, 0) + closest * out;
  return {"passing", true, {P(at_tc - t_c * s * z), P(f0), P(f1), P(f2), P(at_tc + (1 - t_c) * s * z), P(f0), P(f1), P(f2)}, {},
          t_c - std::sqrt(std::max(0.0, kEta * kEta - closest * closest)) / s};
}

/// Edge b (along y, at height h) sliding along x towards the end (1, 0, 0) of edge a (the x axis from −1): the
/// distance reaches √(g² + h²) at t = 1, beyond a's end by g.
Family end_of_edge(double closest, std::mt19937& rng, const Placement& P) {
  std::uniform_real_distribution<double> ang(0.1, 1.4), travel(1, 3);
  const double phi = ang(rng), g = closest * std::cos(phi), h = closest * std::sin(phi), x1 = 1 + g, x0 = x1 + travel(rng);
  const Vec3 a0(-1, 0, 0), a1(1, 0, 0);
  return {"end of edge", false, {}, {P(a0), P(a1), P(Vec3(x0, -1, h)), P(Vec3(x0, 1, h)), P(a0), P(a1), P(Vec3(x1, -1, h)), P(Vec3(x1, 1, h))},
          (x0 - 1 - std::sqrt(std::max(0.0, kEta * kEta - h * h))) / (x0 - x1)};
}

CcdHit run(const ConservativeTester& t, const Family& f) { return f.vf ? t.vertex_face(f.qv) : t.edge_edge(f.qe); }


template <class Check>
void for_each_family(unsigned seed, int per_family, Check check) {
  std::mt19937 rng(seed);
  for (int k = 0; k < per_family; ++k)
    for (const auto make : {sinking, passing, end_of_edge})
      for (const double side : {-1.0, 1.0}) {
        const Placement P = random_placement(rng);
        check(make(kEta * (1 + side * kGap), rng, P), side < 0, P.scale);
      }
}

TEST(SeparationSearch, ReportsEveryPairThatComesWithinEtaAndNoneThatStaysBeyondIt) {
  int hits = 0, misses = 0;
  for_each_family(5, 200, [&](const Family& f, bool within, double scale) {
    // δ well below the 10⁻⁹ gap (relative to the query's size, ~1): undecided boxes cannot hide the answer.
    ConservativeTester::Params p;
    p.thickness = kEta * scale;
    p.delta = 1e-12;
    const CcdHit h = run(ConservativeTester(p), f);
    EXPECT_EQ(h.hit, within) << f.name << " scale " << scale;
    hits += h.hit, misses += !h.hit;
    // Never late; within toi_tolerance when certified (the placement's rounding moves the time by < 10⁻⁹).
    if (h.hit) {
      EXPECT_LE(h.toi, f.toi + 1e-9) << f.name << " scale " << scale;
      if (h.route == TestRoute::main) {
        EXPECT_GE(h.toi, f.toi - p.toi_tolerance - 1e-9) << f.name << " scale " << scale;
      }
    }
  });
  EXPECT_EQ(hits, misses);
}

TEST(SeparationSearch, DefaultDeltaMissesNoneAndCountsTheNearMissesItReports) {
  int near_misses = 0, total = 0;
  for_each_family(6, 200, [&](const Family& f, bool within, double scale) {
    ConservativeTester::Params p;
    p.thickness = kEta * scale;
    const CcdHit h = run(ConservativeTester(p), f);
    if (within) {
      EXPECT_TRUE(h.hit) << f.name << " scale " << scale;
    } else {
      near_misses += h.hit, ++total;
    }
  });
  // δ = 10⁻⁶ of the query's size is above the gap (10⁻⁹ of it): such near misses may be reported, and are counted.
  std::cout << "[ default delta ] near misses at eta (1 + 1e-6) reported: " << near_misses << " of " << total << "\n";
}

TEST(SeparationSearch, TimeIsNeverLateAndWithinToleranceWhenCertified) {
  std::mt19937 rng(8);
  for (int k = 0; k < 300; ++k) {
    const Placement P = random_placement(rng);
    const double eta = kEta * P.scale;
    ConservativeTester::Params p;
    p.thickness = eta;
    p.delta = 1e-12;
    const ConservativeTester t(p);
    // Sinking from a to b < η: distance a + t (b − a) reaches η at (a − η) / (a − b), in the unit frame.
    std::uniform_real_distribution<double> w(0.15, 0.35), up(2, 20), below(0.1, 0.9);
    const Vec3 foot(w(rng), w(rng), 0), z(0, 0, 1);
    const double a = kEta * up(rng), b = kEta * below(rng), toi = (a - kEta) / (a - b);
    const VertexFaceQuery q{P(foot + a * z), P({0, 0, 0}), P({1, 0, 0}), P({0, 1, 0}), P(foot + b * z), P({0, 0, 0}), P({1, 0, 0}), P({0, 1, 0})};
    const CcdHit h = t.vertex_face(q);
    ASSERT_TRUE(h.hit) << k;
    EXPECT_LE(h.toi, toi + 1e-12) << k;
    if (h.route == TestRoute::main) {
      EXPECT_GE(h.toi, toi - p.toi_tolerance - 1e-12) << k;
    }
    // Already within η at the start: the time is 0.
    const VertexFaceQuery q0{P(foot + b * z), P({0, 0, 0}), P({1, 0, 0}), P({0, 1, 0}), P(foot + a * z), P({0, 0, 0}), P({1, 0, 0}), P({0, 1, 0})};
    const CcdHit h0 = t.vertex_face(q0);
    ASSERT_TRUE(h0.hit);
    EXPECT_EQ(h0.toi, 0.0);
  }
}

TEST(SeparationSearch, TiltingEdgeKeepsTheFirstTimeWhereAdvancementStalls) {
  // Edge b sinks slowly towards edge a (the x axis) while tilting fast: its ends move much faster than its
  // closest point, so conservative advancement stalls and the box search has to find the first time. The
  // reference: the first of 10⁵ samples of the distance below η, refined by bisection (the distance falls
  // steadily there).
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> h0(0.02, 0.1), sink(0.5, 1.5), tilt(0.3, 1.0), slide(-0.3, 0.3);
  const double eta = 1e-3;
  ConservativeTester::Params p;
  p.thickness = eta;
  const ConservativeTester t(p);
  int checked = 0;
  for (int k = 0; k < 100; ++k) {
    const double z0 = h0(rng), z1 = z0 - sink(rng) * z0, tz = tilt(rng), sx = slide(rng);
    const EdgeEdgeQuery q{{-1, 0, 0}, {1, 0, 0}, {sx, -1, z0 - tz}, {sx, 1, z0 + tz},
                          {-1, 0, 0}, {1, 0, 0}, {-sx, -1, z1 + tz}, {-sx, 1, z1 - tz}};
    auto distance = [&](double s) {
      auto at = [s](const Vec3& a, const Vec3& b) -> Vec3 { return a + s * (b - a); };
      return std::sqrt(closest_segment_segment(at(q.ea0_t0, q.ea0_t1), at(q.ea1_t0, q.ea1_t1), at(q.eb0_t0, q.eb0_t1),
                                               at(q.eb1_t0, q.eb1_t1)).distance_sq);
    };
    int first = -1;
    for (int i = 0; i <= 100000 && first < 0; ++i)
      if (distance(i / 1e5) <= eta) first = i;
    const CcdHit h = t.edge_edge(q);
    ASSERT_EQ(h.hit, first >= 0) << k;
    if (first <= 0) continue;
    double lo = (first - 1) / 1e5, hi = first / 1e5;
    for (int i = 0; i < 60; ++i) (distance(0.5 * (lo + hi)) <= eta ? hi : lo) = 0.5 * (lo + hi);
    EXPECT_LE(h.toi, hi + 1e-9) << k;
    if (h.route == TestRoute::main) {
      EXPECT_GE(h.toi, lo - p.toi_tolerance - 1e-9) << k;
    }
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(SeparationSearch, ParallelEdgesSlidingAtTheDistanceAreDecided) {
  // Two parallel edges at a constant distance d, sliding along each other: the distance is d over a whole
  // interval of (t, u, v), the hardest case for a bisection. Within η: a hit at t = 0; beyond: none.
  for (const double d : {0.999 * kEta, 1.001 * kEta}) {
    ConservativeTester::Params p;
    p.thickness = kEta;
    const EdgeEdgeQuery q{{0, 0, 0}, {1, 0, 0}, {0.5, d, 0}, {1.5, d, 0}, {0, 0, 0}, {1, 0, 0}, {-0.3, d, 0}, {0.7, d, 0}};
    const CcdHit h = ConservativeTester(p).edge_edge(q);
    EXPECT_EQ(h.hit, d < kEta) << d;
    if (h.hit) {
      EXPECT_EQ(h.toi, 0.0);
    }
  }
}

TEST(SeparationSearch, FarApartNeverHitsAndStillPairsAlwaysHit) {
  ConservativeTester::Params p;
  p.thickness = 0.01;
  const ConservativeTester t(p);
  const Vec3 f0(0, 0, 0), f1(1, 0, 0), f2(0, 1, 0);
  EXPECT_FALSE(t.vertex_face({{0.2, 0.2, 0.5}, f0, f1, f2, {0.2, 0.2, 0.02}, f0, f1, f2}).hit);
  EXPECT_TRUE(t.vertex_face({{0.2, 0.2, 0.005}, f0, f1, f2, {0.2, 0.2, 0.005}, f0, f1, f2}).hit);
  // A vertex of the face itself (distance 0 all step) and a degenerate face (a segment) are handled.
  EXPECT_TRUE(t.vertex_face({f1, f0, f1, f2, f1, f0, f1, f2}).hit);
  EXPECT_TRUE(t.vertex_face({{0.5, 0.005, 0}, f0, f1, f1, {0.5, 0.005, 0}, f0, f1, f1}).hit);
  EXPECT_FALSE(t.vertex_face({{0.5, 0.02, 0}, f0, f1, f1, {0.5, 0.02, 0}, f0, f1, f1}).hit);
}

TEST(SeparationSearch, ConfigRefusesAnExactFallbackWithThickness) {
  const auto& r = tester_registry();
  ParamValues v = r.find("conservative")->defaults();
  v.set("thickness", 1e-4);
  EXPECT_EQ(r.make({"conservative", v})->thickness(), 1e-4);
  v.set("fallback", std::string("exact"));
  EXPECT_THROW((void)r.make({"conservative", v}), Error);
}

}  // namespace
}  // namespace ccdlab
