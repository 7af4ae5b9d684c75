// The narrow phase as a whole: every mode, representative rule, SIMD target and K reports the contacts brute force
// finds; the adaptive passes (stage 4, orphan certificates, the orphan carry) change the work, never the contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <memory>
#include <string>

#include "framework/narrow/kdop_filter.hpp"
#include "framework/narrow/narrow_phase.hpp"
#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "support/registries.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::for_each_simd_target;

/// A tester by name; "conservative+eta" is `conservative` at thickness 0.002 (1/50 of an edge of a 10×10 grid).
std::unique_ptr<PrimitiveTester> make_tester(const std::string& tester) {
  if (tester == "conservative+eta") {
    ParamValues p = tester_registry().find("conservative")->defaults();
    p.set("thickness", 0.002);
    return tester_registry().make({"conservative", p});
  }
  return tester_registry().make({tester, tester_registry().find(tester)->defaults()});
}

PipelineStrategies strategies(const char* tester, NarrowOptions narrow, int k, int threads) {
  PipelineStrategies s;
  s.k = k;
  s.threads = threads;
  s.narrow = narrow;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({"front", scheduler_registry().find("front")->defaults()});
  s.tester = make_tester(tester);
  return s;
}


TEST(NarrowModes, EveryModeRuleTargetAndKReportsTheSameContactsAsBruteForce) {
  MeshData g = test::grid(10, 10);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(9);
  // Testers with a cull reach: the culling stages may only drop pairs they would not report. `additive` and
  // `inclusion` declare none (their hits are not bounded by a distance): the stages that need one stay off.
  for (const char* tester : {"float", "filtered", "conservative", "conservative+eta", "additive", "inclusion"}) {
    Positions x0 = test::crumple(g.positions, rng, 0.03), x1 = x0;
    std::uniform_real_distribution<double> u(-1, 1);
    for (Vec3& p : x1) p += 0.1 * Vec3(u(rng), u(rng), u(rng));
    CollisionRules rules(mesh, single_cloth_body(mesh));
    auto reference = brute_force_contacts(mesh, rules, x0, x1, *strategies(tester, {}, 18, 1).tester, true);
    ASSERT_GT(reference.size(), 5u) << tester;
    const std::uint64_t expect = contact_set_hash(reference);
    for (auto mode : {NarrowMode::scalar, NarrowMode::batched})
      for (auto rule : {RepresentativeRule::fixed, RepresentativeRule::first_free})
        for (auto carry : {PassChoice::off, PassChoice::on})
          for (int k : test::kdop_ks()) {
            if (carry == PassChoice::on && rule == RepresentativeRule::first_free) continue;  // nothing to carry
            CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies(tester, {mode, rule, {.orphan_carry = carry}}, k, 1 + k % 3));
            const StepResult r = pipeline.step(x0, x1);
            EXPECT_EQ(contact_set_hash(r.contacts), expect)
                << tester << " " << to_string(mode) << "/" << to_string(rule) << " K=" << k << " carry " << int(carry);
            if (carry == PassChoice::on) {
              EXPECT_GT(r.counters.orphans_carried, 0u) << tester << " K=" << k;
            }
          }
    for_each_simd_target([&](const char* target) {
      CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies(tester, {}, 18, 2));
      EXPECT_EQ(contact_set_hash(pipeline.step(x0, x1).contacts), expect) << tester << " on " << target;
    });
  }
}

TEST(NarrowModes, StageFourRunsWhereItsMeasuredSavingPaysAndTheContactsStayTheSame) {
  // A crumpled sheet mirrored through its plane, one step replayed: its folds pass through each other, so most
  // pairs that reach stage 4 are contacts. Forced on or off, stage 4 and the sixteenths leave the contacts of
  // brute force; adaptive, the pipeline runs them in its second step exactly when its first step's measured
  // thread-ns say they paid (rules/stage_rules.hpp), whichever way that comes out.
  MeshData g = test::grid(12, 12);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(17);
  const Positions x0 = test::crumple(g.positions, rng, 0.05);
  Positions x1 = x0;
  std::uniform_real_distribution<double> u(-1, 1);
  for (Vec3& p : x1) p.z() = -p.z() + 0.01 * u(rng);
  CollisionRules rules(mesh, single_cloth_body(mesh));
  for (const char* tester : {"float", "conservative"}) {
    const std::uint64_t expect = contact_set_hash(brute_force_contacts(mesh, rules, x0, x1, *make_tester(tester), true));
    for (const PassChoice sixteenths : {PassChoice::on, PassChoice::off})
      for (const PassChoice proximity : {PassChoice::on, PassChoice::off}) {
        CcdPipeline forced(mesh, single_cloth_body(mesh),
                           strategies(tester, {NarrowMode::batched, RepresentativeRule::fixed, {.sixteenths = sixteenths, .proximity = proximity}}, 18, 2));
        for (int s = 0; s < 2; ++s) {
          const StepResult r = forced.step(x0, x1);
          EXPECT_EQ(contact_set_hash(r.contacts), expect) << tester;
          EXPECT_EQ(r.counters.sixteenths_tested > 0, sixteenths == PassChoice::on) << tester;
          EXPECT_EQ(r.counters.proximity_tested > 0, sixteenths == PassChoice::on && proximity == PassChoice::on) << tester;
        }
      }
    CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies(tester, {}, 18, 2));
    const StepResult first = pipeline.step(x0, x1);
    EXPECT_EQ(contact_set_hash(first.contacts), expect) << tester;
    const NarrowCounters& c = first.counters;
    ASSERT_GT(c.proximity_tested, 0u) << tester;
    ASSERT_GT(c.sixteenths_tested, 0u) << tester;
    const double per_test = double(c.test_ns) / double(c.vf_tests + c.ee_tests);
    const double stage4 = CullPassRule::net_saving(double(c.proximity_ns), c.proximity_culled, per_test);
    const bool sixteenths_pay =
        CullPassRule::net_saving(double(c.sixteenths_ns), c.sixteenths_culled, per_test) + std::max(0.0, stage4) > 0;
    const StepResult second = pipeline.step(x0, x1);
    EXPECT_EQ(contact_set_hash(second.contacts), expect) << tester;
    EXPECT_EQ(second.counters.sixteenths_tested > 0, sixteenths_pay) << tester;
    EXPECT_EQ(second.counters.proximity_tested > 0, sixteenths_pay && stage4 > 0) << tester;
  }
}


/// `count` frames of grid `g`: crumpled (0.004), then each vertex jittered by up to `jitter` a step.
std::vector<Positions> drifting_sheet(const MeshData& g, unsigned seed, int count, double jitter) {
  std::mt19937 rng(seed);
  std::vector<Positions> frames{test::crumple(g.positions, rng, 0.004)};
  std::uniform_real_distribution<double> u(-1, 1);
  while (int(frames.size()) < count) {
    frames.push_back(frames.back());
    for (Vec3& p : frames.back()) p += jitter * Vec3(u(rng), u(rng), u(rng));
  }
  return frames;
}


TEST(NarrowModes, OrphanBlocksThatBarelyMovedAreSkippedWithTheSameContacts) {
  // A crumpled sheet that barely moves for a few steps, then one vertex passes through its neighbours (contacts
  // among the orphans) and back: the orphan loop skips blocks from the second step on, except where
  // the vertex moved, and reports the contacts of the scalar mode (which tests every orphan) at every step.
  MeshData g = test::grid(24, 24);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::vector<Positions> frames = drifting_sheet(g, 8, 7, 1e-4);
  frames[3][312] += Vec3(0, 0, 0.1);                           // lifted, then
  frames[4][312] = frames[3][312] + Vec3(0.08, 0.0, -0.11);      // through the sheet beside it, then back
  const NarrowOptions never_carry{NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::off, .certificates = PassChoice::on}};
  CcdPipeline batched(mesh, single_cloth_body(mesh), strategies("float", never_carry, 18, 2));
  CcdPipeline scalar(mesh, single_cloth_body(mesh), strategies("float", {NarrowMode::scalar, RepresentativeRule::fixed, {.orphan_carry = PassChoice::off}}, 18, 1));
  const std::size_t orphans = batched.orphans().vf.size() + batched.orphans().ee.size();
  for (std::size_t s = 0; s + 1 < frames.size(); ++s) {
    const StepResult a = batched.step(frames[s], frames[s + 1]), b = scalar.step(frames[s], frames[s + 1]);
    EXPECT_EQ(contact_set_hash(a.contacts), contact_set_hash(b.contacts)) << "step " << s;
    EXPECT_EQ(a.counters.orphans_unmoved + a.counters.orphan_vf + a.counters.orphan_ee, orphans) << "step " << s;
    if (s == 0) EXPECT_EQ(a.counters.orphans_unmoved, 0u);
    else EXPECT_GT(a.counters.orphans_unmoved, orphans / 2) << "step " << s;
    if (s == 3) {  // contacts among the orphans: the blocks that moved were tested
      const OrphanSet& o = batched.orphans();
      std::size_t among_orphans = 0;
      for (const Contact& c : a.contacts)
        among_orphans += c.kind == ContactKind::vf
                             ? std::count(o.vf.begin(), o.vf.end(), VertexFacePair{c.feature_a, c.feature_b})
                             : std::count(o.ee.begin(), o.ee.end(), EdgeEdgePair{c.feature_a, c.feature_b});
      EXPECT_GT(among_orphans, 0u);
    }
  }
}

TEST(NarrowModes, CandidatesThatCarryTheOrphansFindTheContactsOfAPipelineThatNeverLetsThem) {
  // A cloth that barely moves, with a vertex jumping through its neighbours (contacts among the orphans): the
  // candidates carry the orphans in every step (narrow.rules.orphan_carry: on), and the orphan loop keeps only
  // those no face pair can carry; the contacts are those of a pipeline that never lets them.
  MeshData g = test::grid(24, 24);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::vector<Positions> frames = drifting_sheet(g, 4, 4, 0.004);
  frames[2][300] = frames[1][300] + Vec3(0, 0, 0.3);
  CcdPipeline carrying(mesh, single_cloth_body(mesh), strategies("float", {NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::on}}, 18, 2));
  CcdPipeline never(mesh, single_cloth_body(mesh), strategies("float", {NarrowMode::batched, RepresentativeRule::fixed, {.orphan_carry = PassChoice::off}}, 18, 2));
  const std::size_t orphans = carrying.orphans().vf.size() + carrying.orphans().ee.size();
  bool any_contact = false;
  for (std::size_t s = 0; s + 1 < frames.size(); ++s) {
    const StepResult a = carrying.step(frames[s], frames[s + 1]), b = never.step(frames[s], frames[s + 1]);
    EXPECT_EQ(contact_set_hash(a.contacts), contact_set_hash(b.contacts)) << "step " << s;
    EXPECT_EQ(b.counters.orphans_carried, 0u);
    EXPECT_EQ(b.counters.orphan_vf + b.counters.orphan_ee, orphans);
    EXPECT_GT(a.counters.orphans_carried, 0u) << "step " << s;
    EXPECT_LT(a.counters.orphan_vf + a.counters.orphan_ee, orphans / 10) << "step " << s;
    any_contact |= !a.contacts.empty();
  }
  EXPECT_TRUE(any_contact);
}

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab
