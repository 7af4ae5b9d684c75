// The adaptive rules and their calendar (framework/narrow/rules/stage_rules.hpp), fed measured costs by hand.
#include <gtest/gtest.h>

#include "framework/narrow/rules/stage_rules.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

constexpr std::uint64_t kPeriod = RuleCalendar::kPeriod;

TEST(CullPassRule, RunsWhileWhatItRemovedCostMoreThanItselfAndIsMeasuredAgainWithBackoff) {
  CullPassRule rule;
  EXPECT_TRUE(rule.runs(1)) << "nothing measured yet: it runs";
  // 100 pairs removed at 150 ns a test save 15 µs: a pass of 20 µs does not pay, one of 10 µs does.
  EXPECT_LT(CullPassRule::net_saving(20000, 100, 150), 0);
  EXPECT_GT(CullPassRule::net_saving(10000, 100, 150), 0);
  rule.record(CullPassRule::net_saving(20000, 100, 150));  // switched off: checked again two periods on
  for (std::uint64_t s = 1; s < 2 * kPeriod; ++s) EXPECT_FALSE(rule.runs(s)) << s;
  EXPECT_TRUE(rule.runs(2 * kPeriod)) << "measured again in its slot";
  EXPECT_TRUE(rule.remeasures(2 * kPeriod));
  rule.record(-1);  // confirmed: the interval grows fourfold (to 8 periods)
  EXPECT_FALSE(rule.runs(4 * kPeriod));
  EXPECT_TRUE(rule.runs(8 * kPeriod));
  rule.record(+1);  // it pays now: it runs in every step
  for (std::uint64_t s = 8 * kPeriod + 1; s < 10 * kPeriod; ++s) EXPECT_TRUE(rule.runs(s)) << s;
  EXPECT_FALSE(rule.remeasures(8 * kPeriod + 1));
}

TEST(CullPassRule, ForcedIgnoresWhatItMeasures) {
  CullPassRule on(PassChoice::on), off(PassChoice::off);
  on.record(-1e9), off.record(1e9);
  for (std::uint64_t s = 0; s < 2 * kPeriod; ++s) EXPECT_TRUE(on.runs(s) && !off.runs(s)) << s;
}

TEST(SwitchRule, RunsItsChoiceAndTheOtherInItsSlotThenSwitchesWhenThatCostLess) {
  SwitchRule rule(PassChoice::adaptive, true, RuleCalendar::triangles);
  for (std::uint64_t s = 0; s < kPeriod; ++s) {
    EXPECT_EQ(rule.measures(s), s == RuleCalendar::triangles) << s;
    EXPECT_EQ(rule.runs(s), s != RuleCalendar::triangles) << s;
  }
  rule.measured(120, 0b01);
  rule.reference(100, 0b11);  // a reference that ran other passes: nothing decided
  EXPECT_TRUE(rule.chosen());
  rule.reference(100, 0b01);  // the alternative cost more: kept, measured again four periods on
  EXPECT_TRUE(rule.chosen());
  EXPECT_FALSE(rule.measures(2 * kPeriod + RuleCalendar::triangles));
  EXPECT_TRUE(rule.measures(4 * kPeriod + RuleCalendar::triangles));
  rule.reference(50, 0b01);  // decided already: a later clean step changes nothing
  EXPECT_TRUE(rule.chosen());
  rule.measured(80, 0b01);
  rule.reference(100, 0b01);  // cheaper: switched, checked again two periods on
  EXPECT_FALSE(rule.chosen());
  EXPECT_FALSE(rule.runs(4 * kPeriod + RuleCalendar::triangles + 1));
  EXPECT_FALSE(rule.runs(5 * kPeriod + RuleCalendar::triangles));
  EXPECT_TRUE(rule.runs(6 * kPeriod + RuleCalendar::triangles));
  SwitchRule forced(PassChoice::off, true, RuleCalendar::triangles);
  EXPECT_FALSE(forced.runs(RuleCalendar::triangles) || forced.measures(RuleCalendar::triangles));
}

TEST(SwitchRule, BackoffStopsAtTheLongestInterval) {
  SwitchRule rule(PassChoice::adaptive, false, RuleCalendar::carry);
  for (int i = 0; i < 10; ++i) rule.measured(2, 0), rule.reference(1, 0);
  const std::uint64_t longest = RuleCalendar::kMaxPeriods * kPeriod;
  EXPECT_TRUE(rule.measures(longest + RuleCalendar::carry));
  EXPECT_FALSE(rule.measures(longest / 2 + RuleCalendar::carry));
}

/// A step's counters with `ns` of narrow work.
NarrowCounters costing(std::uint64_t ns) {
  NarrowCounters c;
  c.test_ns = ns;
  c.vf_tests = 1;
  return c;
}

TEST(StageRules, EachRuleMeasuresInItsOwnSlotAgainstTheLastCleanStep) {
  StageRules rules({}, PassChoice::adaptive);
  const StepPossible all{true, true, true, true, true};
  // The first period: each A/B rule tries its other choice once, in its own slot, every other step clean.
  std::vector<int> measuring(kPeriod, 0);
  for (std::uint64_t s = 0; s < kPeriod; ++s) {
    const StepPlan p = rules.plan(s, all);
    EXPECT_EQ(p.triangles, s != RuleCalendar::triangles) << s;  // on until measured off
    EXPECT_EQ(p.end_boxes, s >= RuleCalendar::end_boxes_ready) << s;  // off until tried (a step to warm up, one
                                                                       // measured), cheaper: kept on
    EXPECT_EQ(p.carry, s == RuleCalendar::carry) << s;
    EXPECT_EQ(p.certificates, !p.carry && s != RuleCalendar::certificates) << s;
    EXPECT_EQ(p.clean, s != RuleCalendar::triangles && s != RuleCalendar::carry && s != RuleCalendar::certificates &&
                           s != RuleCalendar::end_boxes_ready && s != RuleCalendar::end_boxes) << s;
    measuring[s] = !p.clean;
    // Every step costs 100 but the end boxes' (50): they switch on, nothing else does (each alternative is judged
    // against the last clean step, which ran the same passes but its own).
    const bool cheap = s == RuleCalendar::end_boxes;
    rules.record(s, p, costing(100), {100, cheap ? 50.0 : 100.0});
  }
  for (std::uint64_t s = kPeriod; s < 2 * kPeriod; ++s) {
    const StepPlan p = rules.plan(s, all);
    EXPECT_TRUE(p.end_boxes) << s;   // switched on: tried off again two periods on
    EXPECT_TRUE(p.triangles) << s;   // confirmed: measured again four periods on
    EXPECT_FALSE(p.carry) << s;
    EXPECT_TRUE(p.clean) << s;
  }
  for (std::uint64_t s = 2 * kPeriod; s < 3 * kPeriod; ++s) {
    const std::uint64_t k = s % kPeriod;
    EXPECT_EQ(rules.plan(s, all).end_boxes, k != RuleCalendar::end_boxes_ready && k != RuleCalendar::end_boxes) << s;
  }
  // Impossible passes never run nor measure.
  const StepPlan none = rules.plan(RuleCalendar::triangles, StepPossible{});
  EXPECT_FALSE(none.triangles || none.sixteenths || none.proximity || none.carry || none.certificates || none.end_boxes);
  EXPECT_TRUE(none.clean);
}

TEST(StageRules, ASwitchMakesEveryOtherRuleMeasureAgainAtItsNextSlot) {
  StageRules rules({}, PassChoice::adaptive);
  const StepPossible all{true, true, true, true, true};
  // Period 0: the end boxes switch on (their step costs 50), the others are confirmed (every other step 100):
  // they would wait four periods. Period 2: the end boxes, measured off again, cost less off and switch back
  // (step 2·16 + 3); stage 0 and the carry, whose slots come later, measure again in that same period.
  for (std::uint64_t s = 0; s < 3 * kPeriod; ++s) {
    const StepPlan p = rules.plan(s, all);
    const std::uint64_t k = s % kPeriod;
    const bool ends_measured = k == RuleCalendar::end_boxes && s / kPeriod != 1;
    if (s >= 2 * kPeriod) {
      EXPECT_EQ(p.carry, k == RuleCalendar::carry) << s;
      EXPECT_EQ(p.triangles, k != RuleCalendar::triangles) << s;
    } else if (s >= kPeriod) {
      EXPECT_TRUE(p.clean) << s;
    }
    rules.record(s, p, costing(100), {100, ends_measured ? 50.0 : 100.0});
  }
  EXPECT_FALSE(rules.plan(3 * kPeriod, all).end_boxes) << "switched back off";
  // Confirmed again there: four periods on.
  for (std::uint64_t s = 3 * kPeriod; s < 4 * kPeriod; ++s) {
    const StepPlan p = rules.plan(s, all);
    EXPECT_TRUE(p.triangles && !p.carry) << s;
  }
}

TEST(StageRules, CertificatesMeasuredOnAreReadiedTheStepBefore) {
  StageRuleChoices c;
  c.certificates = PassChoice::adaptive;
  StageRules rules(c, PassChoice::off);
  const StepPossible can{false, false, false, true, false};
  // Chosen on: measured off in its slot.
  for (std::uint64_t s = 0; s < kPeriod; ++s) {
    const StepPlan p = rules.plan(s, can);
    EXPECT_EQ(p.certificates, s < RuleCalendar::certificates) << s;  // measured off, cheaper: kept off
    rules.record(s, p, costing(100), {s == RuleCalendar::certificates ? 50.0 : 100.0, 100});
  }
  // Switched off: two periods on, the step before the slot readies them, the slot uses them.
  for (std::uint64_t s = 2 * kPeriod; s < 3 * kPeriod; ++s) {
    const StepPlan p = rules.plan(s, can);
    const std::uint64_t k = s % kPeriod;
    EXPECT_EQ(p.certificates, k == RuleCalendar::certificates_ready || k == RuleCalendar::certificates) << s;
    EXPECT_EQ(p.clean, !p.certificates) << s;
  }
}

TEST(StageRules, StageFourRunsOnlyWithTheSixteenthsAndEarnsForThem) {
  StageRules rules({}, PassChoice::off);
  const StepPossible can{false, true, false, false, false};
  StepPlan p = rules.plan(1, can);
  ASSERT_TRUE(p.sixteenths && p.proximity);
  // The sixteenths cost 30 µs and removed 100 pairs (15 µs of tests at 150 ns); stage 4 cost 10 µs and removed
  // 200 (30 µs): together they pay, so both run on.
  NarrowCounters c;
  c.vf_tests = 1000, c.test_ns = 150000;
  c.sixteenths_tested = 1000, c.sixteenths_culled = 100, c.sixteenths_ns = 30000;
  c.proximity_tested = 900, c.proximity_culled = 200, c.proximity_ns = 10000;
  rules.record(1, p, c, {});
  p = rules.plan(2, can);
  EXPECT_TRUE(p.sixteenths && p.proximity);
  // Stage 4 removes nothing any more: both stop (the sixteenths alone do not pay), until slot 0 measures again,
  // two periods on.
  c.proximity_culled = 0;
  rules.record(2, p, c, {});
  for (std::uint64_t s = 3; s < 2 * kPeriod; ++s) EXPECT_FALSE(rules.plan(s, can).sixteenths) << s;
  p = rules.plan(2 * kPeriod, can);
  EXPECT_TRUE(p.sixteenths && p.proximity);
  EXPECT_FALSE(p.clean) << "a step that runs a pass only to measure it is no reference";
}

}  // namespace
}  // namespace ccdlab
