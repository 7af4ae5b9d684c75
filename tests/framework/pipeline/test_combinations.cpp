// Combinatorial differential test: every combination of builder × restructuring × normal cones × scheduler × K
// with the `float` tester, `filtered` and `conservative` against every scheduler × K (the other switches
// cycling), `exact` (slow) against each value of each option, against brute force over several steps of small scenes with many contacts. Together these cover all pairs of
// options and all combinations where they are cheap — the cover that would have caught `sah` + restructuring
// refitting through a stale cut and losing contacts (issue 8).
//
// The references: brute force over every feature pair whose swept feature boxes overlap (no BVH, no ownership,
// no culling) with the same tester must report exactly the pipeline's contacts. The box test is what the
// pipeline also does: `float` and `filtered` may call a near miss between disjoint boxes a hit (within float's
// tolerance) that the pipeline rightly never asks about, and `exact` reports no contact between disjoint boxes. `conservative` may report near misses too, so it must lie between the
// exact contacts (never miss one) and its own brute force.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "strategies/scenes/drape_fold_scene.hpp"
#include "support/registries.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

struct Combination {
  std::string builder;
  bool restructure = false;
  bool cones = false;
  std::string scheduler;
  int k = 18;
  int threads = 1;
  int width = 2;  ///< bv.width: the binary BVTT or the 4-wide view
  [[nodiscard]] std::string label() const {
    return fmt::format("{} restructure={} cones={} {} k={} x{} width={}", builder, restructure, cones, scheduler, k,
                       threads, width);
  }
};

const std::vector<std::string> kBuilders = test::builders();
const std::vector<std::string> kSchedulers = test::bvtt_schedulers();
const std::vector<int> kKs = test::kdop_ks();

/// Every combination of builder × restructure × cones × scheduler × K (128 today: the registries and KdopKs); threads cycle through 1, 2, 3 and
/// the BVH width alternates so that every scheduler × K meets both widths (once with cones, once without).
std::vector<Combination> all_combinations() {
  std::vector<Combination> out;
  for (const auto& b : kBuilders)
    for (bool r : {false, true})
      for (bool c : {false, true})
        for (const auto& s : kSchedulers)
          for (int k : kKs) {
            const std::size_t i = out.size();
            out.push_back({b, r, c, s, k, 1 + int(i % 3), 2 + 2 * int((i / 16 + i) % 2)});
          }
  return out;
}

/// Every scheduler × K (16 today), with builder, restructuring, cones and threads cycling so that each
/// of their values meets each scheduler and each K.
std::vector<Combination> scheduler_k_cover() {
  std::vector<Combination> out;
  int i = 0;
  for (const auto& s : kSchedulers)
    for (int k : kKs) {
      out.push_back({kBuilders[std::size_t(i % 2)], (i / 2) % 2 == 1, (i / 4 + i) % 2 == 1, s, k, 1 + i % 3,
                     2 + 2 * ((i / 4 + i / 2) % 2)});
      ++i;
    }
  return out;
}

/// 4 combinations in which every scheduler, every K and both values of every switch appear: all pairs of the
/// (slow) `exact` tester with each option value.
std::vector<Combination> one_of_each() {
  return {{"median", false, false, "sequential", 6, 1, 4},
          {"sah", true, false, "phc", 14, 2, 2},
          {"median", true, true, "front", 18, 3, 4},
          {"sah", false, true, "static", 26, 2, 4}};
}

PipelineStrategies strategies(const Combination& c, const std::string& tester) {
  PipelineStrategies s;
  s.k = c.k;
  s.width = c.width;
  s.threads = c.threads;
  s.restructure_threshold = c.restructure ? 1.01 : 0;  // aggressive: rebuild at the slightest degradation
  s.normal_cones = c.cones;
  s.builder = builder_registry().make({c.builder, builder_registry().find(c.builder)->defaults()});
  s.scheduler = scheduler_registry().make({c.scheduler, scheduler_registry().find(c.scheduler)->defaults()});
  s.tester = tester_registry().make({tester, tester_registry().find(tester)->defaults()});
  s.narrow.rules = StageRuleChoices::all(PassChoice::on);  // timed rules may choose differently between runs
  s.end_boxes = EndBoxMode::on;
  return s;
}

/// A crumpled 12×10 sheet whose folds move from one random crumple to the next: many self-contacts in every
/// step and sub-trees that degrade (so restructuring rebuilds them).
MeshSequence crumpled_sheet() {
  const MeshData g = test::grid(12, 10);
  std::mt19937 rng(2024);
  std::vector<Positions> keys;
  for (int i = 0; i < 3; ++i) keys.push_back(test::crumple(g.positions, rng, 0.01));
  constexpr int kPerKey = 3;
  auto frames = std::make_shared<std::vector<Positions>>();
  for (std::size_t k = 0; k + 1 < keys.size(); ++k)
    for (int j = 0; j < kPerKey; ++j) {
      const double t = double(j) / kPerKey;
      Positions x = keys[k];
      for (std::size_t v = 0; v < x.size(); ++v) x[v] = (1 - t) * keys[k][v] + t * keys[k + 1][v];
      frames->push_back(std::move(x));
    }
  frames->push_back(keys.back());
  TriMesh mesh(g.positions.size(), g.faces);
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < frames->size(); ++i) labels.push_back(std::to_string(i));
  auto bodies = single_cloth_body(mesh);
  return MeshSequence(std::move(mesh), bodies, labels, [frames](int i) { return (*frames)[std::size_t(i)]; },
                      "crumpled sheet");
}

/// The built-in scene, small: a folding sheet draped over a moving sphere (two bodies, self and pair passes).
MeshSequence small_drape_fold() {
  DrapeFoldParams p;
  p.resolution = 10;
  p.frames = 7;
  p.fold_deg = 230;
  p.sphere_segments = 8;
  return make_drape_fold_scene(p);
}

using Keys = std::vector<std::tuple<ContactKind, Index, Index>>;
Keys keys(const Contacts& cs) {
  Keys k;
  for (const Contact& c : cs) k.push_back(c.key());
  std::sort(k.begin(), k.end());
  return k;
}

/// Brute-force contact keys of every step of a scene for one tester, computed once and shared.
const std::vector<Keys>& reference(const std::string& scene_name, const MeshSequence& scene, const std::string& tester) {
  static std::map<std::pair<std::string, std::string>, std::vector<Keys>> cache;
  auto [it, fresh] = cache.try_emplace({scene_name, tester});
  if (fresh) {
    const auto t = tester_registry().make({tester, tester_registry().find(tester)->defaults()});
    const CollisionRules rules(scene.topology(), scene.bodies());
    // `exact` never reports a contact between disjoint swept feature boxes (touching features lie in both
    // closed boxes), so culling its brute force by the boxes changes no answer and saves most exact tests.
    const bool box_cull = tester != "conservative";
    for (int s = 0; s < scene.num_steps(); ++s)
      it->second.push_back(
          keys(brute_force_contacts(scene.topology(), rules, scene.frame(s), scene.frame(s + 1), *t, box_cull)));
  }
  return it->second;
}

struct SceneCase {
  std::string name;
  MeshSequence (*make)();
};

struct Param {
  SceneCase scene;
  std::string tester;
  friend void PrintTo(const Param& p, std::ostream* os) { *os << p.scene.name << " " << p.tester; }
};

class Combinations : public ::testing::TestWithParam<Param> {};

TEST_P(Combinations, EveryCombinationMatchesBruteForce) {
  const Param& param = GetParam();
  const MeshSequence scene = param.scene.make();
  const bool conservative = param.tester == "conservative";
  const std::vector<Keys>& expected = reference(param.scene.name, scene, param.tester);
  const std::vector<Keys>* exact = conservative ? &reference(param.scene.name, scene, "exact") : nullptr;
  std::size_t contacts = 0;
  for (const Keys& k : expected) contacts += k.size();
  ASSERT_GE(contacts, std::size_t(40 * scene.num_steps())) << "the scene must collide a lot, or the test proves little";

  const auto combos = param.tester == "float" ? all_combinations() : param.tester == "exact" ? one_of_each() : scheduler_k_cover();
  std::uint64_t restructured = 0;
  for (const Combination& c : combos) {
    SCOPED_TRACE(c.label());
    CcdPipeline pipeline(scene.topology(), scene.bodies(), strategies(c, param.tester));
    Positions x0 = scene.frame(0);
    for (int s = 0; s < scene.num_steps(); ++s) {
      Positions x1 = scene.frame(s + 1);
      const StepResult r = pipeline.step(x0, x1);
      restructured += r.counters.restructured;
      const Keys got = keys(r.contacts);
      if (conservative) {
        EXPECT_TRUE(std::includes(got.begin(), got.end(), (*exact)[s].begin(), (*exact)[s].end())) << "missed an exact contact at step " << s;
        EXPECT_TRUE(std::includes(expected[s].begin(), expected[s].end(), got.begin(), got.end())) << "step " << s;
      } else {
        EXPECT_EQ(got, expected[s]) << "step " << s << ": " << got.size() << " contacts, brute force " << expected[s].size();
      }
      x0 = std::move(x1);
    }
    if (::testing::Test::HasFailure()) return;  // one failing combination says enough
  }
  EXPECT_GT(restructured, 0u) << "restructuring must actually rebuild sub-trees in these scenes";
}

std::string name_of(const ::testing::TestParamInfo<Param>& info) { return info.param.scene.name + "_" + info.param.tester; }

const SceneCase kCrumpled{"crumpled", &crumpled_sheet};
const SceneCase kDrape{"drape_fold", &small_drape_fold};

INSTANTIATE_TEST_SUITE_P(AllOptions, Combinations,
                         ::testing::Values(Param{kCrumpled, "float"}, Param{kDrape, "float"}, Param{kCrumpled, "filtered"},
                                           Param{kDrape, "filtered"}, Param{kCrumpled, "conservative"},
                                           Param{kDrape, "conservative"}, Param{kCrumpled, "exact"}, Param{kDrape, "exact"}),
                         name_of);

}  // namespace
}  // namespace ccdlab

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

// A memory-bounded step streams its candidates slice by slice: the same contacts and BV tests as the whole
// traversal at once, for every scheduler (the front is rebuilt per slice), on a scene with many contacts.
TEST(MemoryBoundedSteps, StreamingSlicesGiveTheSameAnswer) {
  const MeshSequence scene = crumpled_sheet();
  for (const std::string& scheduler : kSchedulers)
    for (std::size_t slices : {std::size_t(1), std::size_t(7), std::size_t(200)}) {
      SCOPED_TRACE(scheduler + " slices=" + std::to_string(slices));
      const Combination c{"sah", true, false, scheduler, 18, 2};
      CcdPipeline whole(scene.topology(), scene.bodies(), strategies(c, "float"));
      PipelineStrategies streamed_strategies = strategies(c, "float");
      streamed_strategies.stream_slices = slices;
      CcdPipeline streamed(scene.topology(), scene.bodies(), std::move(streamed_strategies));
      Positions x0 = scene.frame(0);
      for (int s = 0; s < scene.num_steps(); ++s) {
        Positions x1 = scene.frame(s + 1);
        const StepResult a = whole.step(x0, x1), b = streamed.step(x0, x1);
        EXPECT_EQ(keys(b.contacts), keys(a.contacts)) << "step " << s;
        EXPECT_EQ(b.counters.candidate_pairs, a.counters.candidate_pairs) << "step " << s;
        EXPECT_EQ(b.counters.vf_tests + b.counters.ee_tests, a.counters.vf_tests + a.counters.ee_tests) << "step " << s;
        if (scheduler != "front") {
          EXPECT_EQ(b.counters.bv_tests, a.counters.bv_tests) << "step " << s;
        }
        EXPECT_EQ(b.memory.slices, slices);
        x0 = std::move(x1);
      }
    }
}

TEST(MemoryBoundedSteps, PlanStreamsOnlyAboveTheBudget) {
  MemoryBudget none(0);
  const MemoryPlan unlimited = none.plan(1u << 30, 1000000);
  EXPECT_FALSE(unlimited.streamed);
  EXPECT_EQ(unlimited.expected_pairs, 1000000 * MemoryBudget::kFirstStepCandidatesPerFace) << "first-step guess";
  none.record(1000, 0);
  EXPECT_EQ(none.plan(1u << 30, 1000000).expected_pairs, 1250u) << "the last step's pairs and a quarter";
  MemoryBudget roomy(std::uint64_t(8) << 30);
  EXPECT_FALSE(roomy.plan(std::uint64_t(1) << 30, 100000).streamed);  // 100K faces: ~51 MB predicted
  MemoryBudget tight(std::uint64_t(300) << 20);
  // 1M faces: ~512 MB predicted; 100 MB left, half of it the candidates' (the other half the contacts').
  const MemoryPlan p = tight.plan(std::uint64_t(200) << 20, 1000000);
  EXPECT_TRUE(p.streamed);
  EXPECT_EQ(p.budget_bytes, std::uint64_t(50) << 20);
  EXPECT_GE(p.slices, 16u * 10);
  EXPECT_EQ(p.flush_pairs, (std::uint64_t(50) << 20) / MemoryBudget::kBytesPerCandidate / 2);
  EXPECT_THROW((void)tight.plan(std::uint64_t(400) << 20, 10), Error);  // resident alone above the limit
  tight.record(1000, 0);  // measured: tiny steps now, no streaming needed
  EXPECT_FALSE(tight.plan(std::uint64_t(200) << 20, 1000000).streamed);
  // A step estimated to explode (work_estimate.hpp) streams whatever the last one found; the next plan forgets it.
  tight.expect(1e8);
  EXPECT_TRUE(tight.plan(std::uint64_t(200) << 20, 1000000).streamed);
  tight.record(1000, 0);
  EXPECT_FALSE(tight.plan(std::uint64_t(200) << 20, 1000000).streamed);
}

TEST(MemoryBoundedSteps, FitsIsWhetherThePlanRunsUnstreamed) {
  // The pipeline keeps last step's candidate pages only when fits() says yes with them resident.
  MemoryBudget none(0);
  EXPECT_TRUE(none.fits(std::uint64_t(1) << 40, 1000000)) << "no limit: always";
  MemoryBudget tight(std::uint64_t(300) << 20);
  for (const std::uint64_t resident : {std::uint64_t(200) << 20, std::uint64_t(299) << 20, std::uint64_t(1) << 20})
    for (const std::size_t faces : {std::size_t(10), std::size_t(100000), std::size_t(1000000)}) {
      const bool fits = tight.fits(resident, faces);
      EXPECT_EQ(fits, !tight.plan(resident, faces).streamed) << resident << " resident, " << faces << " faces";
    }
  EXPECT_FALSE(tight.fits(std::uint64_t(400) << 20, 10)) << "resident above the limit: no, and no throw";
  tight.record(1000, 0);
  EXPECT_TRUE(tight.fits(std::uint64_t(200) << 20, 1000000));
  MemoryBudget forced(0, 4);
  EXPECT_FALSE(forced.fits(0, 10)) << "forced slices always stream";
}

}  // namespace
}  // namespace ccdlab
