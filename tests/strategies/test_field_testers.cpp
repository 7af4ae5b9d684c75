// The field's two methods on the ladder: `inclusion` (Wang et al. 2021) never misses — the hard cases, random
// near contacts and uniform queries checked against `exact`, the shared sets and scaled / translated copies —
// and bounds the time of contact from below; `additive` (Li et al. 2021) on a worked example, what its hits
// mean (pairs that approach, not only contacts), and its misses and false hits counted, not hidden.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "framework/queries/evaluate.hpp"
#include "framework/queries/hard_cases.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "strategies/testers/additive_tester.hpp"
#include "strategies/testers/exact_tester.hpp"
#include "strategies/testers/float_tester.hpp"
#include "strategies/testers/inclusion_tester.hpp"
#include "support/random_queries.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::decide;
using test::run;

/// Every collision of `s` (exact's answer on the query as given) is a hit of `t`, never later than exact's time.
void expect_no_miss(const PrimitiveTester& t, const ExactTester& exact, const QuerySet& s, const std::string& what) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const ExactTester::Decision d = decide(exact, s, i);
    if (!d.hit) continue;
    const CcdHit h = run(t, s, i);
    ASSERT_TRUE(h.hit) << what << " " << s.origin[i] << " #" << i;
    EXPECT_LE(h.toi, d.toi_hi) << what << " " << s.origin[i] << " #" << i;
  }
}

TEST(Inclusion, NeverMissesAHardCaseOrARandomQueryAndBoundsTheTimeFromBelow) {
  const ExactTester exact;
  for (const double delta : {1e-2, 1e-6}) {
    const InclusionTester inclusion({delta, InclusionTester::Params{}.max_boxes, 0.0});
    const std::string what = "delta " + std::to_string(delta);
    for (const auto& s : hard_case_sets()) expect_no_miss(inclusion, exact, s, what);
    for (const ContactKind kind : {ContactKind::vf, ContactKind::ee})
      for (const double jitter : {0.0, 1e-9, 1e-4})
        expect_no_miss(inclusion, exact, test::random_near_contacts(kind, 200, jitter, 31 + unsigned(jitter * 1e4)), what);
  }
  // Uniform random segments and triangles moving in a cube: about one in five collides, in any configuration.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  QuerySet vf, ee;
  vf.kind = ContactKind::vf, ee.kind = ContactKind::ee;
  for (int k = 0; k < 400; ++k) {
    vf.vf.push_back({rv(), rv(), rv(), rv(), rv(), rv(), rv(), rv()});
    ee.ee.push_back({rv(), rv(), rv(), rv(), rv(), rv(), rv(), rv()});
    vf.origin.push_back("uniform vf #" + std::to_string(k));
    ee.origin.push_back("uniform ee #" + std::to_string(k));
  }
  expect_no_miss(InclusionTester(), exact, vf, "uniform");
  expect_no_miss(InclusionTester(), exact, ee, "uniform");
}

TEST(Inclusion, WithAMinimumSeparationReportsWhatFloatReportsAtThatDistance) {
  // ms bounds each coordinate of the gap, so a pair within distance ms (every coordinate within it) is a hit:
  // every pair `float` reports at thickness ms, and every contact.
  const ExactTester exact;
  std::size_t hits = 0, float_hits = 0;
  for (const double ms : {1e-6, 1e-3}) {
    const InclusionTester inclusion({1e-6, InclusionTester::Params{}.max_boxes, ms});
    const FloatTester flt({ms});
    for (const ContactKind kind : {ContactKind::vf, ContactKind::ee})
      for (const double jitter : {0.0, 1e-6, 1e-3}) {
        const QuerySet s = test::random_near_contacts(kind, 100, jitter, 41 + unsigned(jitter * 1e3));
        expect_no_miss(inclusion, exact, s, "ms " + std::to_string(ms));
        for (std::size_t i = 0; i < s.size(); ++i) {
          const bool f = run(flt, s, i).hit, h = run(inclusion, s, i).hit;
          if (f) {
            EXPECT_TRUE(h) << "ms " << ms << " " << to_string(kind) << " jitter " << jitter << " #" << i;
          }
          float_hits += f, hits += h;
        }
      }
  }
  EXPECT_GT(float_hits, 300u);
  EXPECT_GE(hits, float_hits);
}

TEST(Inclusion, SharedQuerySetsAndTheirScaledAndMovedCopiesNoMiss) {
  const std::string root = test::shared_data();
  if (root.empty()) GTEST_SKIP() << "../shared/data not found: shared query sets skipped";
  const InclusionTester inclusion;
  const ExactTester exact;
  std::size_t total = 0;
  for (const auto& s : load_query_sets(root + "/ccd-queries")) {
    const SetScore c = score(s, "inclusion", run_tester(inclusion, s), {});
    EXPECT_EQ(c.false_negatives, 0u) << s.name;
    total += s.size();
  }
  EXPECT_GT(total, 17000u);
  // Copies scaled by 1e-3 / 1e3 and moved 1e6 away: the reference is exact on the copy (rounding may change the
  // question where the features keep only a few digits).
  for (const char* file : {"/ccd-queries/simulation/cloth-funnel/queries/227ee.csv", "/ccd-queries/simulation/cloth-funnel/queries/227vf.csv"})
    for (const double scale : {1e-3, 1e3})
      for (const Vec3& shift : {Vec3(0, 0, 0), Vec3(1e6, -1e6, 1e6)}) {
        QuerySet s = load_query_sets(root + file).at(0);
        auto move = [&](Vec3& p) { p = scale * p + shift; };
        for (auto& q : s.vf) for (Vec3* p : {&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1}) move(*p);
        for (auto& q : s.ee) for (Vec3* p : {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1}) move(*p);
        expect_no_miss(inclusion, exact, s, std::string(file) + " x" + std::to_string(scale));
      }
}

TEST(Additive, AdvancesByTheFractionOfTheGapAndStopsBeforeTheLastStep) {
  // A vertex falling straight onto a still face, touching at t* = 0.5: the approach bound is the vertex's speed
  // exactly, so each step closes 0.9 of the gap left; the second step would leave less than 0.1 of the start
  // gap, so the answer is the time after the first, 0.9 t*.
  const Vec3 f0(0, 0, 0), f1(1, 0, 0), f2(0, 1, 0);
  const AdditiveTester additive;
  const CcdHit h = additive.vertex_face({{0.25, 0.25, 1}, f0, f1, f2, {0.25, 0.25, -1}, f0, f1, f2});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.toi, 0.45, 1e-12);
  EXPECT_EQ(h.route, TestRoute::main);
  // Edge b dropping across edge a, meeting at t* = 0.25: the same 0.9 t*.
  const CcdHit e = additive.edge_edge({{-1, 0, 0}, {1, 0, 0}, {0, -1, 0.5}, {0, 1, 0.5},
                                       {-1, 0, 0}, {1, 0, 0}, {0, -1, -1.5}, {0, 1, -1.5}});
  ASSERT_TRUE(e.hit);
  EXPECT_NEAR(e.toi, 0.225, 1e-12);
  // With a minimum separation ξ the gap is d − ξ: the features stop 0.9 of the way to distance ξ.
  const CcdHit s = AdditiveTester({0.9, 0.2, 10000}).vertex_face({{0.25, 0.25, 1}, f0, f1, f2, {0.25, 0.25, -1}, f0, f1, f2});
  ASSERT_TRUE(s.hit);
  EXPECT_NEAR(s.toi, 0.9 * 0.4, 1e-12);
}

TEST(Additive, PairsThatApproachAreHitsACommonTranslationIsNot) {
  const Vec3 f0(0, 0, 0), f1(1, 0, 0), f2(0, 1, 0), up(0, 0, 5);
  const AdditiveTester additive;
  // Moving together: the distance never changes, whatever the speed.
  EXPECT_FALSE(additive.vertex_face({{0.25, 0.25, 1}, f0, f1, f2, Vec3(0.25, 0.25, 1) + up, f0 + up, f1 + up, f2 + up}).hit);
  // Passing 0.05 beside the face's edge x = 0 without touching: the gap falls below 0.1 of its start, a hit (the
  // line search's stop) at the time before the step that would take it there.
  const CcdHit near = additive.vertex_face({{-0.05, 0.25, 1}, f0, f1, f2, {-0.05, 0.25, -1}, f0, f1, f2});
  EXPECT_TRUE(near.hit);
  EXPECT_LT(near.toi, 0.5);
  EXPECT_FALSE(ExactTester().decide(VertexFaceQuery{{-0.05, 0.25, 1}, f0, f1, f2, {-0.05, 0.25, -1}, f0, f1, f2}).hit);
  // From 1 to 0.2: never that close, no hit.
  EXPECT_FALSE(additive.vertex_face({{0.25, 0.25, 1}, f0, f1, f2, {0.25, 0.25, 0.2}, f0, f1, f2}).hit);
  // Touching at the start.
  EXPECT_EQ(additive.vertex_face({{0.25, 0.25, 0}, f0, f1, f2, {0.25, 0.25, 1}, f0, f1, f2}).toi, 0.0);
}

TEST(Additive, MissesAndFalseHitsAreCountedAndTimesAreNotLate) {
  // Not conservative in floating point: misses are counted, not asserted; where it reports a collision exact also
  // finds, its time (a step it would take) is before the contact.
  const AdditiveTester additive;
  const ExactTester exact;
  std::size_t misses = 0, false_hits = 0, queries = 0;
  auto count = [&](const QuerySet& s) {
    for (std::size_t i = 0; i < s.size(); ++i, ++queries) {
      const ExactTester::Decision d = decide(exact, s, i);
      const CcdHit h = run(additive, s, i);
      misses += d.hit && !h.hit, false_hits += !d.hit && h.hit;
      if (d.hit && h.hit) {
        EXPECT_LE(h.toi, d.toi_hi + 1e-12) << s.origin[i] << " #" << i;
      }
    }
  };
  for (const auto& s : hard_case_sets()) count(s);
  for (const ContactKind kind : {ContactKind::vf, ContactKind::ee})
    for (const double jitter : {0.0, 1e-6, 1e-3}) count(test::random_near_contacts(kind, 200, jitter, 53 + unsigned(jitter * 1e3)));
  std::cout << "[ additive ] " << queries << " queries: misses " << misses << ", false hits " << false_hits << "\n";
  ::testing::Test::RecordProperty("additive_misses", int(misses));
  EXPECT_GT(false_hits, 0u) << "pairs that approach without touching are hits by design";
}

TEST(FieldTesters, ParametersOutsideTheirRangeAreRefusedByName) {
  const auto refuses = [](auto make, const char* field) {
    try {
      make();
      ADD_FAILURE() << "accepted " << field;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  refuses([] { AdditiveTester({1.0, 0, 10}); }, "tester.eta");
  refuses([] { AdditiveTester({0.9, -1, 10}); }, "tester.thickness");
  refuses([] { AdditiveTester({0.9, 0, 0}); }, "tester.max_iterations");
  refuses([] { InclusionTester({-1, 10, 0}); }, "tester.delta");
  refuses([] { InclusionTester({1e-6, 10, std::nan("")}); }, "tester.min_separation");
  // Through the registry, as YAML and --tester reach them.
  EXPECT_EQ(tester_registry().make({"inclusion", tester_registry().find("inclusion")->defaults()})->name(), "inclusion");
  EXPECT_EQ(tester_registry().make({"additive", tester_registry().find("additive")->defaults()})->name(), "additive");
}

}  // namespace
}  // namespace ccdlab
