// The accuracy ladder (float, filtered, conservative, exact; additive and inclusion in test_field_testers.cpp) on
// queries with known answers: the built-in hard
// cases, random near-degenerate queries checked against `exact`, and the shared benchmark sets (skipped where
// ../shared/data is absent). `exact` must agree with every known answer, `conservative` must never miss;
// `float` and `filtered` failures are counted and printed, not asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <set>
#include <algorithm>

#include "framework/queries/evaluate.hpp"
#include "framework/queries/hard_cases.hpp"
#include "strategies/testers/conservative_tester.hpp"
#include "strategies/testers/exact_tester.hpp"
#include "strategies/testers/filtered_tester.hpp"
#include "strategies/testers/float_tester.hpp"
#include "strategies/testers/interval_ccd.hpp"
#include "support/random_queries.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::decide;
using test::run;

TEST(AccuracyLadder, HardCasesCoverEveryFamilyOfTheIssue) {
  std::set<std::string> names;
  std::size_t queries = 0, hits = 0;
  for (const auto& s : hard_case_sets()) names.insert(s.name), queries += s.size(), hits += std::count(s.truth.begin(), s.truth.end(), 1);
  for (const char* family : {"contact-at-t0", "contact-at-t1", "vertex-on-edge", "vertex-on-vertex", "coplanar-motion",
                             "zero-area-face", "no-motion", "two-roots", "edges-contact-at-t1", "edge-end-on-edge",
                             "parallel-edges", "collinear-edges", "zero-length-edge", "edges-no-motion",
                             "tiny-motion-vf", "tiny-motion-ee", "large-coordinates-vf", "large-coordinates-ee", "tilted-vf", "tilted-ee"})
    EXPECT_TRUE(names.count(std::string("hard-cases/") + family)) << family;
  EXPECT_GT(queries, 500u);
  EXPECT_GT(hits, 100u);
  EXPECT_GT(queries - hits, 200u);
}

TEST(AccuracyLadder, ExactAgreesWithEveryHardCaseAndItsTimeOfContact) {
  double widest = 0;
  for (const bool prefilter : {true, false})
  for (const bool certify : {true, false}) {
    const ExactTester exact({prefilter, certify});
    for (const auto& s : hard_case_sets())
      for (std::size_t i = 0; i < s.size(); ++i) {
        const auto d = decide(exact, s, i);
        ASSERT_EQ(d.hit, s.truth[i] != 0) << s.origin[i] << (prefilter ? "" : " (no prefilter)")
                                          << (certify ? "" : " (no certification)");
        if (d.hit) {
          EXPECT_LE(d.toi_lo, d.toi_hi);
          // Within a couple of ulps from the algebra; as narrow as interval bounds prove when certified.
          EXPECT_LE(d.toi_hi - d.toi_lo, d.prefiltered ? 0x1p-30 : 2.3e-16) << s.origin[i];
          widest = std::max(widest, d.prefiltered ? d.toi_hi - d.toi_lo : 0.0);
        }
        if (!std::isnan(s.toi[i])) {  // known exactly; 1/3 itself is not a double, hence the 1e-16 slack
          EXPECT_GE(s.toi[i] + 1e-16, d.toi_lo) << s.origin[i];
          EXPECT_LE(s.toi[i] - 1e-16, d.toi_hi) << s.origin[i];
        }
      }
  }
  std::cout << "[exact] widest certified time-of-contact enclosure: " << widest << "\n";
}

TEST(AccuracyLadder, ConservativeNeverMissesAHardCaseAndBoundsTheTimeFromBelow) {
  const ExactTester exact;
  for (const auto fallback : {ConservativeTester::Fallback::hit, ConservativeTester::Fallback::exact})
    for (const double delta : {1e-2, 1e-6, 0.0}) {
      const ConservativeTester c({delta, fallback, 512, 1e-6});
      std::size_t false_hits = 0;
      for (const auto& s : hard_case_sets())
        for (std::size_t i = 0; i < s.size(); ++i) {
          const CcdHit h = run(c, s, i);
          if (s.truth[i]) {
            ASSERT_TRUE(h.hit) << s.origin[i] << " delta=" << delta;
            EXPECT_LE(h.toi, decide(exact, s, i).toi_hi) << s.origin[i];
          } else {
            false_hits += h.hit;
          }
        }
      // With the exact fallback nothing is left to chance; with "hit", near misses within ~delta may be hits.
      if (fallback == ConservativeTester::Fallback::exact) {
        EXPECT_EQ(false_hits, 0u) << "delta=" << delta;
      }
      std::cout << "[ conservative delta=" << delta << (fallback == ConservativeTester::Fallback::exact ? " exact" : " hit")
                << " ] false hits on hard cases: " << false_hits << "\n";
    }
}

TEST(AccuracyLadder, FloatAndFilteredFailuresAreCountedNotHidden) {
  const FloatTester flt;
  const FilteredTester filtered;
  const ExactTester exact;
  std::size_t fn[2] = {0, 0}, fp[2] = {0, 0}, total = 0;
  for (const auto& s : hard_case_sets())
    for (std::size_t i = 0; i < s.size(); ++i, ++total) {
      const CcdHit a = run(flt, s, i), b = run(filtered, s, i);
      fn[0] += s.truth[i] && !a.hit, fp[0] += !s.truth[i] && a.hit;
      fn[1] += s.truth[i] && !b.hit, fp[1] += !s.truth[i] && b.hit;
      // The filter is certified: whatever it culls, exact also rejects.
      if (b.route == TestRoute::filter) {
        EXPECT_FALSE(decide(exact, s, i).hit) << s.origin[i];
      }
    }
  std::cout << "[ hard cases: " << total << " ] float misses " << fn[0] << ", false hits " << fp[0]
            << "; filtered misses " << fn[1] << ", false hits " << fp[1] << "\n";
  ::testing::Test::RecordProperty("float_false_negatives", int(fn[0]));
  ::testing::Test::RecordProperty("filtered_false_negatives", int(fn[1]));
}

TEST(AccuracyLadder, PowerOfTwoScalingChangesNoAnswerOfAnyTester) {
  // Scaling by 2^k is exact, so a scale-invariant tester must answer exactly as before.
  const FloatTester flt;
  const FilteredTester filtered;
  const ConservativeTester conservative;
  const ExactTester exact;
  const PrimitiveTester* testers[] = {&flt, &filtered, &conservative, &exact};
  for (const auto& s : hard_case_sets()) {
    if (s.name.find("tiny-motion") != std::string::npos || s.name.find("large-coordinates") != std::string::npos) continue;
    for (const double scale : {0x1p-30, 0x1p-10, 0x1p10, 0x1p30}) {
      QuerySet scaled = s;
      for (auto& q : scaled.vf)
        for (Vec3* p : {&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1}) *p *= scale;
      for (auto& q : scaled.ee)
        for (Vec3* p : {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1}) *p *= scale;
      for (const PrimitiveTester* t : testers)
        for (std::size_t i = 0; i < s.size(); ++i)
          EXPECT_EQ(run(*t, s, i).hit, run(*t, scaled, i).hit) << t->name() << " " << s.origin[i] << " x " << scale;
    }
  }
}

TEST(AccuracyLadder, ConservativeNeverMissesWhatExactFindsOnRandomNearContacts) {
  const ExactTester exact;
  const ConservativeTester conservative;
  const ConservativeTester resolved({1e-9, ConservativeTester::Fallback::exact, 512, 1e-6});
  const FilteredTester filtered;
  for (const ContactKind kind : {ContactKind::vf, ContactKind::ee})
    for (const double jitter : {0.0, 1e-12, 1e-6, 1e-3}) {
      const QuerySet s = test::random_near_contacts(kind, 300, jitter, 7 + unsigned(jitter * 1e3));
      std::size_t hits = 0;
      for (std::size_t i = 0; i < s.size(); ++i) {
        const auto d = decide(exact, s, i);
        hits += d.hit;
        const CcdHit c = run(conservative, s, i), r = run(resolved, s, i), f = run(filtered, s, i);
        if (d.hit) {
          ASSERT_TRUE(c.hit) << to_string(kind) << " jitter " << jitter << " #" << i;
          EXPECT_LE(c.toi, d.toi_hi);
        }
        EXPECT_EQ(r.hit, d.hit) << to_string(kind) << " jitter " << jitter << " #" << i;
        if (f.route == TestRoute::filter) {
          EXPECT_FALSE(d.hit);
        }
      }
      if (jitter == 0) {
        EXPECT_GT(hits, 250u) << "the generator should aim at contacts";
      }
    }
}

/// What narrow_root must equal or narrow: bisection of a contact window by classify alone.
std::pair<double, double> bisect_by_classify(const interval_ccd::RelativeMotion& m, double a, double b) {
  while (true) {
    const double mid = 0.5 * (a + b);
    if (!(mid > a && mid < b)) return {a, b};
    const interval_ccd::Verdict v = interval_ccd::classify(m, a, mid, true);
    if (v == interval_ccd::Verdict::separated) a = mid;
    else if (v == interval_ccd::Verdict::contact) b = mid;
    else return {a, b};
  }
}

TEST(AccuracyLadder, ExactNarrowsAContactWindowWithinWhatClassifyAloneProvesAroundTheAlgebraicRoot) {
  // The first contact window of each query (as exact's certification finds it: windows of 2^-12 where f may
  // vanish, earlier ones separated), narrowed by narrow_root's subdivided bounds, must lie within bisection by
  // classify alone, and hold the earliest root the algebra (no certification) finds.
  const ExactTester algebra({false, false});
  std::size_t checked = 0, narrower = 0;
  auto check = [&](const auto& q, const std::string& origin) {
    const interval_ccd::RelativeMotion m = interval_ccd::relative_motion(q);
    interval_ccd::for_each_coplanarity_window(m, 0.0, 1.0, 0x1p-12, [&](double a, double b) {
      const interval_ccd::Verdict v = interval_ccd::classify(m, a, b);
      if (v != interval_ccd::Verdict::contact) return v == interval_ccd::Verdict::unknown;  // skip the query
      const auto [lo, hi] = interval_ccd::narrow_root(m, a, b);
      const auto [ref_lo, ref_hi] = bisect_by_classify(m, a, b);
      EXPECT_LE(ref_lo, lo) << origin;
      EXPECT_LE(hi, ref_hi) << origin;
      EXPECT_LT(lo, hi) << origin;
      const ExactTester::Decision d = algebra.decide(q);
      EXPECT_TRUE(d.hit) << origin;
      EXPECT_LE(lo, d.toi_hi) << origin;
      EXPECT_LE(d.toi_lo, hi) << origin;
      ++checked;
      narrower += hi - lo < ref_hi - ref_lo;
      return true;
    });
  };
  auto check_set = [&](const QuerySet& s) {
    for (std::size_t i = 0; i < s.size(); ++i)
      s.kind == ContactKind::vf ? check(s.vf[i], s.origin[i]) : check(s.ee[i], s.origin[i]);
  };
  for (const ContactKind kind : {ContactKind::vf, ContactKind::ee})
    check_set(test::random_near_contacts(kind, 300, 0.0, 19 + unsigned(kind)));
  for (const auto& s : hard_case_sets()) check_set(s);
  EXPECT_GT(checked, 400u);
  std::cout << "[exact] contact windows narrowed: " << checked << ", narrower than classify alone: " << narrower
            << "\n";
}

TEST(AccuracyLadder, ConservativeNeverMissesWhatExactFindsOnUniformRandomQueries) {
  // Random segments and triangles moving in a cube: about one query in five collides, in any configuration.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  const ExactTester exact;
  const ConservativeTester conservative;
  const ConservativeTester resolved({1e-6, ConservativeTester::Fallback::exact, 512, 1e-6});
  const FloatTester flt;
  std::size_t hits = 0, float_wrong = 0;
  for (int k = 0; k < 1500; ++k) {
    const bool vf = k % 2 == 0;
    const VertexFaceQuery qv{rv(), rv(), rv(), rv(), rv(), rv(), rv(), rv()};
    const EdgeEdgeQuery qe{rv(), rv(), rv(), rv(), rv(), rv(), rv(), rv()};
    const auto d = vf ? exact.decide(qv) : exact.decide(qe);
    const CcdHit c = vf ? conservative.vertex_face(qv) : conservative.edge_edge(qe);
    const CcdHit r = vf ? resolved.vertex_face(qv) : resolved.edge_edge(qe);
    hits += d.hit;
    if (d.hit) {
      ASSERT_TRUE(c.hit) << "query " << k;
      EXPECT_LE(c.toi, d.toi_hi) << "query " << k;
    }
    EXPECT_EQ(r.hit, d.hit) << "query " << k;
    float_wrong += (vf ? flt.vertex_face(qv) : flt.edge_edge(qe)).hit != d.hit;
  }
  EXPECT_GT(hits, 100u);
  std::cout << "[ uniform random: 1500 ] collisions " << hits << ", float wrong " << float_wrong << "\n";
}

TEST(AccuracyLadder, ConservativeWithASeparationFindsWhatExactAndFloatFind) {
  // At thickness η, `conservative` reports every pair that comes within η: all of exact's contacts (distance 0),
  // never later, and every pair `float` reports at η (it checks the distance only at its candidate times).
  const ExactTester exact;
  std::size_t beyond_float = 0;
  for (const double eta : {1e-8, 1e-4, 1e-2}) {
    ConservativeTester::Params p;
    p.thickness = eta;
    const ConservativeTester conservative(p);
    const FloatTester flt({eta});
    for (const ContactKind kind : {ContactKind::vf, ContactKind::ee})
      for (const double jitter : {0.0, 1e-6, 1e-3}) {
        const QuerySet s = test::random_near_contacts(kind, 150, jitter, 17 + unsigned(jitter * 1e3));
        for (std::size_t i = 0; i < s.size(); ++i) {
          const auto d = decide(exact, s, i);
          const CcdHit c = run(conservative, s, i), f = run(flt, s, i);
          const std::string what = std::string(to_string(kind)) + " eta " + std::to_string(eta) + " jitter " + std::to_string(jitter) + " #" + std::to_string(i);
          if (d.hit) {
            ASSERT_TRUE(c.hit) << what;
            EXPECT_LE(c.toi, d.toi_hi) << what;
          }
          if (f.hit) {
            ASSERT_TRUE(c.hit) << what;
          }
          beyond_float += c.hit && !f.hit;
        }
      }
  }
  std::cout << "[ separation ] pairs within eta that float does not report: " << beyond_float << "\n";
}

TEST(AccuracyLadder, SharedQuerySetsExactIsRightConservativeNeverMisses) {
  const std::string root = test::shared_data();
  if (root.empty()) GTEST_SKIP() << "../shared/data not found: shared query sets skipped";
  const ExactTester exact;
  const ConservativeTester conservative;
  ConservativeTester::Params p;
  p.thickness = 1e-6;
  const ConservativeTester separated(p);
  std::size_t total = 0;
  for (const auto& s : load_query_sets(root + "/ccd-queries")) {
    const auto outcomes_c = run_tester(conservative, s);
    const auto outcomes_s = run_tester(separated, s);
    const auto outcomes_e = run_tester(exact, s);
    std::vector<ToiReference> ref;
    for (const auto& o : outcomes_e) ref.push_back({o.hit, o.toi, o.toi});
    const SetScore e = score(s, "exact", outcomes_e, {}), c = score(s, "conservative", outcomes_c, ref),
                   d = score(s, "conservative eta", outcomes_s, ref);
    EXPECT_EQ(e.false_negatives + e.false_positives, 0u) << s.name;
    EXPECT_EQ(c.false_negatives, 0u) << s.name;
    EXPECT_EQ(d.false_negatives, 0u) << s.name << " at thickness 1e-6";
    total += s.size();
  }
  EXPECT_GT(total, 17000u);
}

TEST(AccuracyLadder, FunnelAnswersSurviveScalingAndFarTranslation) {
  // The public ICCD code's absolute cut-offs make it find none of the funnel's 134 collisions; our tolerances
  // are relative. Scaling by 1e-3 / 1e3 and translating by 1e6 round the coordinates, which turns the few
  // contacts that touch exactly (a vertex exactly on an edge) into a slightly different question: the
  // reference for a transformed query is therefore `exact` on that query, and we count how often rounding
  // alone changed the answer.
  const std::string root = test::shared_data();
  if (root.empty()) GTEST_SKIP() << "../shared/data not found: funnel query sets skipped";
  const FloatTester flt;
  const ConservativeTester conservative;
  const ExactTester exact;
  for (const char* file : {"/ccd-queries/simulation/cloth-funnel/queries/227ee.csv", "/ccd-queries/simulation/cloth-funnel/queries/227vf.csv"}) {
    const QuerySet base = load_query_sets(root + file).at(0);
    for (const double scale : {1e-3, 1.0, 1e3})
      for (const Vec3& shift : {Vec3(0, 0, 0), Vec3(1e6, -1e6, 1e6)}) {
        QuerySet s = base;
        auto move = [&](Vec3& p) { p = scale * p + shift; };
        for (auto& q : s.vf) for (Vec3* p : {&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1}) move(*p);
        for (auto& q : s.ee) for (Vec3* p : {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1}) move(*p);
        std::size_t rounding_changed = 0, float_wrong = 0;
        for (std::size_t i = 0; i < s.size(); ++i) {
          const bool truth = decide(exact, s, i).hit;
          rounding_changed += truth != (base.truth[i] != 0);
          EXPECT_TRUE(!truth || run(conservative, s, i).hit) << file << " x" << scale << " #" << i;
          float_wrong += run(flt, s, i).hit != truth;
        }
        EXPECT_EQ(float_wrong, 0u) << file << " x" << scale << " +" << shift.transpose();
        // Features ~1e-5 in size at 1e6 keep only ~6 digits: there rounding may change the question itself.
        const bool well_resolved = shift.norm() == 0 || scale >= 1.0;
        if (well_resolved) {
          EXPECT_EQ(rounding_changed, 0u) << file << " x" << scale << " +" << shift.transpose();
        }
        std::cout << "[ " << file << " x" << scale << " +(" << shift.transpose() << ") ] answers changed by rounding: "
                  << rounding_changed << ", float wrong: " << float_wrong << "\n";
      }
  }
}

}  // namespace
}  // namespace ccdlab
