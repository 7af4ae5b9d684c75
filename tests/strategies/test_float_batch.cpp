// The `float` tester's batched root search (float_roots.hpp) gives the scalar tester's answers bit for bit (hit,
// time of contact, coordinates) on every SIMD target: on random near contacts at every scale, on exact-integer
// queries whose cubics have roots and touching points at breakpoints, on coplanar motions (the crossing times'
// kernel), on the built-in hard cases and on the shared query sets (skipped where ../shared/data is absent).
// The kernel's answers are all exercised;
// `filtered`, which hands what its filter leaves to the batch, answers as its scalar self. The distance check at
// the roots equals closest_point_triangle and closest_segment_segment in every region they distinguish.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "framework/geometry/distance.hpp"
#include "framework/queries/hard_cases.hpp"
#include "framework/queries/query_set.hpp"
#include "strategies/testers/filtered_tester.hpp"
#include "strategies/testers/float_roots.hpp"
#include "strategies/testers/float_tester.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

bool same_bits(const CcdHit& a, const CcdHit& b) {
  return a.hit == b.hit && a.route == b.route && std::bit_cast<std::uint64_t>(a.toi) == std::bit_cast<std::uint64_t>(b.toi) &&
         std::bit_cast<std::uint64_t>(a.coords[0]) == std::bit_cast<std::uint64_t>(b.coords[0]) &&
         std::bit_cast<std::uint64_t>(a.coords[1]) == std::bit_cast<std::uint64_t>(b.coords[1]);
}

/// Random queries near contact at scales 1e-4 … 1e2 and offsets up to 1e3: a vertex (or edge) passing through,
/// beside or just short of a face (edge), some with the face turning so the cubic has two or three roots. Every
/// 7th is built on a small integer grid, where f often has exact zeros at 0, 1 and at f′'s roots.
struct RandomQueries {
  std::vector<VertexFaceQuery> vf;
  std::vector<EdgeEdgeQuery> ee;
};
RandomQueries random_queries(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), scale(-4, 2), offset(-3, 3);
  std::uniform_int_distribution<int> grid(-2, 2);
  RandomQueries r;
  for (int i = 0; i < n; ++i) {
    const bool integer = i % 7 == 0;
    const double s = integer ? 1.0 : std::pow(10.0, scale(rng));
    const Vec3 o = integer ? Vec3(Vec3::Zero()) : Vec3(Vec3(u(rng), u(rng), u(rng)) * std::pow(10.0, offset(rng)));
    const auto point = [&](double z) {
      return integer ? Vec3(grid(rng), grid(rng), grid(rng) % 2) : Vec3(o + s * Vec3(u(rng), u(rng), z * u(rng)));
    };
    const auto moved = [&](const Vec3& p, double amount) {
      return integer ? Vec3(p + Vec3(grid(rng), grid(rng), grid(rng))) : Vec3(p + amount * s * Vec3(u(rng), u(rng), u(rng)));
    };
    const double turn = i % 3 == 0 ? 1.0 : 0.05;  // a third of the faces turn a lot: several roots
    std::array<Vec3, 8> p;
    for (int k = 0; k < 4; ++k) p[k] = point(k == 0 ? 1.0 : 0.05);
    p[4] = integer ? moved(p[0], 0) : Vec3(p[0] - Vec3(0, 0, 2 * (p[0] - o).z()) + 0.3 * s * Vec3(u(rng), u(rng), 0));
    for (int k = 1; k < 4; ++k) p[4 + k] = moved(p[k], turn);
    if (i % 11 == 0) p[4] = p[0];  // a still vertex
    r.vf.push_back({p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]});
    // EE: edge (p0, p1) against (p2, p3), the first crossing the second's line.
    r.ee.push_back({p[1], p[2], p[0], p[3], p[5], p[6], p[4], p[7]});
  }
  return r;
}

/// Point k of row i of PointColumns at time t, as the kernel computes it (x0 + t·dx).
Vec3 columns_point(const std::vector<double>& columns, std::size_t stride, std::size_t i, int k, double t) {
  const auto at = [&](int column) { return columns[stride * std::size_t(column) + i]; };
  const int c = PointColumns::P0x + 6 * k;
  return Vec3(at(c), at(c + 1), at(c + 2)) + t * Vec3(at(c + 3), at(c + 4), at(c + 5));
}

template <class Query>
void expect_batch_equals_scalar(const PrimitiveTester& tester, const std::vector<Query>& queries, const std::string& what,
                                std::size_t* hits = nullptr) {
  std::vector<CcdHit> batch(queries.size());
  if constexpr (std::is_same_v<Query, VertexFaceQuery>) tester.vertex_faces(queries, batch.data());
  else tester.edge_edges(queries, batch.data());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    CcdHit scalar;
    if constexpr (std::is_same_v<Query, VertexFaceQuery>) scalar = tester.vertex_face(queries[i]);
    else scalar = tester.edge_edge(queries[i]);
    if (!same_bits(batch[i], scalar) && differ++ < 5)
      ADD_FAILURE() << what << " query " << i << ": batch " << batch[i].hit << " t=" << batch[i].toi << ", scalar "
                    << scalar.hit << " t=" << scalar.toi;
    if (hits) *hits += scalar.hit;
  }
  EXPECT_EQ(differ, 0u) << what;
}

/// Batch = scalar on both kinds of a family, whose answers are both well represented (more than 300 hits and
/// fewer than 90%): the comparison is not between two "no".
void expect_batch_equals_scalar_with_both_answers(const FloatTester& tester, const RandomQueries& r, const std::string& what) {
  std::size_t vf_hits = 0, ee_hits = 0;
  expect_batch_equals_scalar(tester, r.vf, what + " VF", &vf_hits);
  expect_batch_equals_scalar(tester, r.ee, what + " EE", &ee_hits);
  for (const std::size_t hits : {vf_hits, ee_hits}) {
    EXPECT_GT(hits, 300u) << what;
    EXPECT_LT(hits, r.vf.size() * 9 / 10) << what;
  }
}

TEST(FloatBatch, EverySimdTargetGivesTheScalarAnswersBitForBit) {
  const RandomQueries r = random_queries(6000, 11);
  test::for_each_simd_target([&](const char* target) {
    for (const double thickness : {0.0, 1e-3}) {
      const FloatTester tester({thickness});
      const std::string what = std::string(target) + " thickness " + std::to_string(thickness);
      expect_batch_equals_scalar_with_both_answers(tester, r, what);
      if (thickness == 0) continue;
      // With thickness the batch answers at each end of the step and between them by its own routes: all occur.
      std::array<int, 3> at{};  // hits at t = 0, between, at t = 1
      const auto count = [&](const CcdHit& h) {
        if (h.hit) ++at[h.toi == 0 ? 0 : h.toi == 1 ? 2 : 1];
      };
      for (const VertexFaceQuery& q : r.vf) count(tester.vertex_face(q));
      for (const EdgeEdgeQuery& q : r.ee) count(tester.edge_edge(q));
      EXPECT_GT(at[0], 100) << what;
      EXPECT_GT(at[1], 100) << what;
      EXPECT_GT(at[2], 20) << what;
    }
  });
}

/// Coplanar motion (f ≡ 0), where the candidates are the times a point crosses a line in the plane: four points
/// in a plane (axis-aligned, exactly planar, or turned, planar to rounding) moving within it at scales 1e-4 … 1e2,
/// the first point (the vertex; edge a's first end) passing over the others' segment or beside it. The batch's
/// coplanar kernel answers nearly all of them itself, and equals the scalar tester bit for bit on every target.
TEST(FloatBatch, CoplanarMotionGivesTheScalarAnswersBitForBit) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1, 1), scale(-4, 2);
  RandomQueries r;
  for (int i = 0; i < 3000; ++i) {
    const double s = std::pow(10.0, scale(rng));
    Vec3 e1 = Vec3::UnitX(), e2 = Vec3::UnitY();
    if (i % 3 != 0) {  // a turned plane
      e1 = Vec3(u(rng), u(rng), u(rng)).normalized();
      e2 = e1.unitOrthogonal();
    }
    const Vec3 o = Vec3(u(rng), u(rng), u(rng)) * 10 * s;
    const auto in_plane = [&](double a, double b) { return Vec3(o + s * (a * e1 + b * e2)); };
    std::array<Vec3, 8> p;
    for (int k = 1; k < 4; ++k) p[k] = in_plane(u(rng), u(rng));
    const double side = i % 2 == 0 ? 0.2 : 1.5;  // over the other features, or beside them
    p[0] = in_plane(-side - 0.5 * std::abs(u(rng)), u(rng));
    p[4] = in_plane(side + 0.5 * std::abs(u(rng)), u(rng));
    for (int k = 1; k < 4; ++k) p[4 + k] = p[k] + s * 0.1 * (u(rng) * e1 + u(rng) * e2);
    if (i % 5 == 0) p[5] = p[1];  // a still point
    r.vf.push_back({p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]});
    r.ee.push_back({p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]});
  }
  // The kernel's own share: rows it leaves to the scalar tester are few.
  for (const bool vf : {true, false}) {
    const std::size_t n = r.vf.size(), kStride = n + 8;
    std::vector<double> columns(PointColumns::count * kStride, 0.0), times(kCoplanarSlots * kStride);
    std::vector<std::uint8_t> scalar(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<Vec3, 8> q = vf ? std::array<Vec3, 8>{r.vf[i].v_t0, r.vf[i].f0_t0, r.vf[i].f1_t0, r.vf[i].f2_t0,
                                                             r.vf[i].v_t1, r.vf[i].f0_t1, r.vf[i].f1_t1, r.vf[i].f2_t1}
                                       : std::array<Vec3, 8>{r.ee[i].ea0_t0, r.ee[i].ea1_t0, r.ee[i].eb0_t0, r.ee[i].eb1_t0,
                                                             r.ee[i].ea0_t1, r.ee[i].ea1_t1, r.ee[i].eb0_t1, r.ee[i].eb1_t1};
      Box3 box;
      for (int k = 0; k < 4; ++k) {
        box.grow(q[k]), box.grow(q[k + 4]);
        for (int axis = 0; axis < 3; ++axis) {
          columns[kStride * std::size_t(PointColumns::P0x + 6 * k + axis) + i] = q[k][axis] - q[0][axis];
          columns[kStride * std::size_t(PointColumns::dP0x + 6 * k + axis) + i] = q[k + 4][axis] - q[k][axis];
        }
      }
      columns[kStride * PointColumns::extent + i] = box.extent().norm();
    }
    std::vector<double> cubic(CubicColumns::count * kStride);
    cubic_columns(columns.data(), kStride, n, vf ? PointPairing::vertex_face : PointPairing::edge_edge, cubic.data());
    test::for_each_simd_target([&](const char* target) {
      std::vector<FirstRoot> kind(n);
      std::vector<double> t(n);
      std::vector<std::uint8_t> more(n);
      first_coplanar_roots(cubic.data(), kStride, n, FloatTester::rel_tolerance, kind.data(), t.data(), more.data());
      EXPECT_EQ(std::size_t(std::count(kind.begin(), kind.end(), FirstRoot::coplanar)), n) << target;
      coplanar_times(columns.data(), kStride, n, vf ? PointPairing::vertex_face : PointPairing::edge_edge, times.data(),
                     scalar.data());
      std::size_t left = 0, crossings = 0;
      for (std::size_t i = 0; i < n; ++i) {
        left += scalar[i];
        for (int slot = 2; slot < kCoplanarSlots; ++slot) crossings += times[kStride * std::size_t(slot) + i] <= 1.0;
      }
      EXPECT_LT(left, n / 20) << target << (vf ? " VF" : " EE");
      EXPECT_GT(crossings, n) << target << (vf ? " VF" : " EE");
    });
  }
  test::for_each_simd_target([&](const char* target) {
    for (const double thickness : {0.0, 1e-3}) {
      const FloatTester tester({thickness});
      const std::string what = std::string(target) + " coplanar, thickness " + std::to_string(thickness);
      expect_batch_equals_scalar_with_both_answers(tester, r, what);
    }
  });
}

TEST(FloatBatch, FilteredBatchGivesItsScalarAnswers) {
  const RandomQueries r = random_queries(3000, 23);
  const FilteredTester tester;
  std::size_t hits = 0, culled = 0;
  std::vector<CcdHit> batch(r.ee.size());
  tester.edge_edges(r.ee, batch.data());
  for (const CcdHit& h : batch) culled += h.route == TestRoute::filter;
  expect_batch_equals_scalar(tester, r.vf, "filtered VF", &hits);
  expect_batch_equals_scalar(tester, r.ee, "filtered EE", &hits);
  EXPECT_GT(hits, 300u);
  EXPECT_GT(culled, 300u);  // the filter decides some, `float` the rest
  EXPECT_LT(culled, 2700u);
}

TEST(FloatBatch, HardCasesGiveTheScalarAnswersBitForBit) {
  const FloatTester tester;
  test::for_each_simd_target([&](const char* target) {
    for (const QuerySet& s : hard_case_sets()) {
      if (s.kind == ContactKind::vf) expect_batch_equals_scalar(tester, s.vf, std::string(target) + " " + s.name);
      else expect_batch_equals_scalar(tester, s.ee, std::string(target) + " " + s.name);
    }
  });
}

TEST(FloatBatch, SharedQuerySetsGiveTheScalarAnswersBitForBit) {
  const std::string root = test::shared_data();
  if (root.empty()) GTEST_SKIP() << "../shared/data not found: shared query sets skipped";
  const FloatTester tester;
  std::size_t queries = 0;
  for (const QuerySet& s : load_query_sets(root + "/ccd-queries")) {
    queries += s.size();
    if (s.kind == ContactKind::vf) expect_batch_equals_scalar(tester, s.vf, s.name);
    else expect_batch_equals_scalar(tester, s.ee, s.name);
  }
  EXPECT_GT(queries, 0u);
}

/// The kernel's answers on the random family, straight from its columns: every kind occurs, `more` too, and
/// roots at a breakpoint where f touches zero (the integer-grid rows: t exactly 0 or 1, which a refined root never
/// is — the refinement stays a guard inside its bracket).
TEST(FloatBatch, KernelAnswersEveryKind) {
  const RandomQueries r = random_queries(2000, 5);
  constexpr std::size_t kStride = 2008;
  std::vector<double> columns(CubicColumns::count * kStride, 0.0);
  for (std::size_t i = 0; i < r.vf.size(); ++i) {
    const VertexFaceQuery& q = r.vf[i];
    const Vec3 A0 = q.v_t0 - q.f0_t0, B0 = q.f1_t0 - q.f0_t0, C0 = q.f2_t0 - q.f0_t0;
    const Vec3 dA = (q.v_t1 - q.f0_t1) - A0, dB = (q.f1_t1 - q.f0_t1) - B0, dC = (q.f2_t1 - q.f0_t1) - C0;
    const std::array<const Vec3*, 6> vectors{&A0, &dA, &B0, &dB, &C0, &dC};
    for (int v = 0; v < 6; ++v)
      for (int axis = 0; axis < 3; ++axis) columns[kStride * std::size_t(3 * v + axis) + i] = (*vectors[v])[axis];
    const double L = 10 * (A0.norm() + B0.norm() + C0.norm());
    columns[kStride * CubicColumns::f_scale + i] = L * L * L;
  }
  test::for_each_simd_target([&](const char* target) {
    std::vector<FirstRoot> kind(r.vf.size());
    std::vector<double> t(r.vf.size());
    std::vector<std::uint8_t> more(r.vf.size());
    first_coplanar_roots(columns.data(), kStride, r.vf.size(), FloatTester::rel_tolerance, kind.data(), t.data(), more.data());
    std::array<int, 4> count{};
    int with_more = 0, touching = 0;
    for (std::size_t i = 0; i < kind.size(); ++i) {
      ++count[int(kind[i])];
      if (kind[i] == FirstRoot::root) {
        EXPECT_GE(t[i], 0.0) << target;
        EXPECT_LE(t[i], 1.0) << target;
        with_more += more[i];
        touching += t[i] == 0.0 || t[i] == 1.0;
      }
    }
    EXPECT_GT(count[int(FirstRoot::none)], 20) << target;
    EXPECT_GT(count[int(FirstRoot::root)], 500) << target;
    EXPECT_GT(count[int(FirstRoot::scalar)], 0) << target;  // a root of f′ at ±0
    EXPECT_GT(with_more, 20) << target;
    EXPECT_GT(touching, 20) << target;
    // Asked for their next candidate, the rows with `more` have one, later than the first.
    std::vector<std::uint8_t> skip(kind.size());
    for (std::size_t i = 0; i < kind.size(); ++i) skip[i] = kind[i] == FirstRoot::root && more[i];
    std::vector<FirstRoot> kind2(kind.size());
    std::vector<double> t2(kind.size());
    std::vector<std::uint8_t> more2(kind.size());
    first_coplanar_roots(columns.data(), kStride, r.vf.size(), FloatTester::rel_tolerance, kind2.data(), t2.data(),
                         more2.data(), skip.data());
    for (std::size_t i = 0; i < kind.size(); ++i) {
      if (!skip[i]) {
        EXPECT_TRUE(kind2[i] == kind[i] && t2[i] == t[i] && more2[i] == more[i]) << target << " row " << i;
        continue;
      }
      EXPECT_EQ(kind2[i], FirstRoot::root) << target << " row " << i;
      EXPECT_GE(t2[i], t[i]) << target << " row " << i;
    }
  });
}

/// Rows of four moving points and a time, at scales 1e-4 … 1e2: every region of the point–triangle distance and
/// every clamp of the segment–segment one, plus degenerate triangles and point-like edges (which the kernel must
/// leave to the scalar functions) and parallel edges (which it decides, bit for bit too). Half the reaches are the
/// scalar distance itself, where a last-bit difference in the kernel's distance flips the verdict.
TEST(FloatBatch, DistanceAtRootsGivesTheClosestFunctionsBitForBit) {
  constexpr std::size_t n = 4000, kStride = n + 8;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), scale(-4, 2), unit(0, 1);
  std::vector<double> columns(PointColumns::count * kStride, 0.0);
  std::vector<std::array<Vec3, 4>> at(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::pow(10.0, scale(rng)), t = i % 5 == 0 ? double(i % 2) : unit(rng);
    std::array<Vec3, 4> x0, dx;
    for (int k = 0; k < 4; ++k) x0[k] = s * Vec3(u(rng), u(rng), u(rng)), dx[k] = s * Vec3(u(rng), u(rng), u(rng));
    if (i % 13 == 0) x0[3] = 2.0 * x0[2] - x0[1], dx[3] = 2.0 * dx[2] - dx[1];  // a collinear triangle P1 P2 P3
    else if (i % 17 == 0) x0[1] = x0[0], dx[1] = dx[0];                           // a point-like edge P0 P1
    else if (i % 19 == 0) x0[3] = x0[2] + 0.5 * (x0[1] - x0[0]), dx[3] = dx[2] + 0.5 * (dx[1] - dx[0]);  // parallel edges
    for (int k = 0; k < 4; ++k)
      for (int axis = 0; axis < 3; ++axis) {
        columns[kStride * std::size_t(PointColumns::P0x + 6 * k + axis) + i] = x0[k][axis];
        columns[kStride * std::size_t(PointColumns::dP0x + 6 * k + axis) + i] = dx[k][axis];
      }
    columns[kStride * PointColumns::t + i] = t;
    for (int k = 0; k < 4; ++k) at[i][k] = columns_point(columns, kStride, i, k, t);
  }
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  for (const bool vf : {true, false}) {
    std::vector<double> dist(n);
    std::vector<std::array<double, 2>> coords(n);
    std::vector<bool> special(n);
    std::array<int, 8> regions{};
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = at[i];
      if (vf) {
        const PointTriangleClosest c = closest_point_triangle(p[0], p[1], p[2], p[3]);
        dist[i] = c.distance_sq, coords[i] = {c.bary[1], c.bary[2]};
        special[i] = i % 13 == 0;
        // The region by which barycentric weights are zero or one: 7 kinds, one of them the interior.
        const int zeros = (c.bary[0] == 0) + (c.bary[1] == 0) + (c.bary[2] == 0);
        ++regions[zeros == 2 ? 0 : zeros == 1 ? 1 : 2];
      } else {
        const SegmentSegmentClosest c = closest_segment_segment(p[0], p[1], p[2], p[3]);
        dist[i] = c.distance_sq, coords[i] = {c.s, c.t};
        special[i] = i % 13 != 0 && i % 17 == 0;  // parallel edges (i % 19) are the kernel's own
        ++regions[3 + (c.s == 0 || c.s == 1) + 2 * (c.t == 0 || c.t == 1)];
      }
      columns[kStride * PointColumns::reach + i] = i % 2 ? std::sqrt(dist[i]) : std::sqrt(dist[i]) * (0.5 + unit(rng));
    }
    test::for_each_simd_target([&](const char* target) {
      std::vector<AtTime> verdict(n);
      std::vector<double> out(2 * n);
      if (vf) vertex_faces_at(columns.data(), kStride, n, verdict.data(), out.data());
      else edge_edges_at(columns.data(), kStride, n, verdict.data(), out.data());
      std::array<int, 3> count{};
      int differ = 0, special_decided = 0, parallel_decided = 0;
      for (std::size_t i = 0; i < n; ++i) {
        ++count[int(verdict[i])];
        if (verdict[i] == AtTime::scalar) continue;
        special_decided += special[i];
        parallel_decided += !vf && i % 13 != 0 && i % 17 != 0 && i % 19 == 0;
        const double reach = columns[kStride * PointColumns::reach + i];
        const bool hit = dist[i] <= reach * reach;
        if ((verdict[i] == AtTime::hit) != hit || bits(out[2 * i]) != bits(coords[i][0]) || bits(out[2 * i + 1]) != bits(coords[i][1]))
          if (differ++ < 5) ADD_FAILURE() << target << (vf ? " VF" : " EE") << " row " << i;
      }
      EXPECT_EQ(differ, 0) << target;
      EXPECT_EQ(special_decided, 0) << target << (vf ? " VF" : " EE") << ": a degenerate row decided in SIMD";
      if (!vf) {
        EXPECT_GT(parallel_decided, 150) << target << ": parallel edges left to the scalar function";
      }
      EXPECT_GT(count[int(AtTime::hit)], 500) << target;
      EXPECT_GT(count[int(AtTime::miss)], 500) << target;
    });
    EXPECT_GT(std::count(special.begin(), special.end(), true), 200);
    // The rows reach every kind of closest point: vertex, edge, interior (VF); each clamp (EE).
    for (int r = vf ? 0 : 3; r < (vf ? 3 : 7); ++r) EXPECT_GT(regions[r], 100) << (vf ? "VF" : "EE") << " region " << r;
  }
}

}  // namespace
}  // namespace ccdlab
