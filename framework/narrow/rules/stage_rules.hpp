#pragma once
// When a pass that only saves work runs: the adaptive rules of one pipeline and their one re-measuring calendar.
//
//   stage 0        candidate face pairs proven apart before their gather (triangle_filter.hpp)   A/B
//   sixteenths     stage 3's second pass (split_filter.hpp)                                     own cost vs tests saved
//   stage 4        the features' distance on the open windows (window_distance_filter.hpp)            own cost vs tests saved
//   orphan carry   the candidates bring the orphans they carry (representatives.hpp)            A/B
//   certificates   orphan blocks skipped while their motion leaves them apart (orphan_certificates.hpp)  A/B
//   end boxes      the traversal drops node pairs apart at both ends of the step (swept/end_boxes.hpp)  A/B
//
// Every rule decides from what this run measured, never from constants tuned on some scene (design.md):
// - a culling pass (the sixteenths, stage 4) is worth its own measured thread-ns when the pairs it removed, each
//   priced at this step's measured thread-ns per elementary test, cost more; the sixteenths also earn what stage 4,
//   which works on their windows, saved. A pass that did not pay is measured again in the calendar's `passes` slot.
// - an A/B rule runs its current choice in every step and, in its own slot of the calendar, the other one; it
//   switches when that step cost less than a clean step (every rule on its choice) that ran the same passes but
//   its own: the last one before, or the first one after. It assumes neighbouring steps alike in kind (a replay's
//   steps, a solver's successive calls); where they are not, it can choose wrong (docs/narrow-phase.md).
// The passes are exact culling: the contacts are the same whatever a rule decides, only the time moves. Timed
// decisions may differ between runs and schedules; what a step *counts* (tests, pairs) then differs with them,
// so the tests that compare work across schedules force every rule (PassChoice::on / off, StageRuleChoices).
// Each re-measurement that confirms a choice makes the rule's interval four times longer, up to kMaxPeriods
// periods; after a switch it is two periods, so a long run spends few steps on the worse choice and a change of
// regime is still seen. An A/B rule's switch also makes every other rule measure again at its next slot: their
// choices were measured with the old one, and the passes interact (stage 0 decides how much the orphan carry
// costs, say), so rules that each decide with the others fixed could otherwise sit on a worse combination for
// periods.
#include <array>
#include <cstdint>
#include <utility>
#include <string_view>

#include "framework/narrow/narrow_counters.hpp"
#include "framework/util/named_values.hpp"

namespace ccdlab {

/// A rule's setting: decided by measurement (`auto`), or forced.
enum class PassChoice { adaptive, on, off };
/// Its names (YAML's booleans among them): the one list every reader and message takes.
inline constexpr NamedValues<PassChoice, 5> kPassChoices{{{{"auto", PassChoice::adaptive},
                                                           {"on", PassChoice::on},
                                                           {"off", PassChoice::off},
                                                           {"true", PassChoice::on},
                                                           {"false", PassChoice::off}}}};
[[nodiscard]] inline std::string_view to_string(PassChoice c) { return kPassChoices.name_of(c); }

/// narrow.rules: one setting per rule (bv.end_boxes is the end boxes' own, EndBoxMode).
struct StageRuleChoices {
  PassChoice triangles = PassChoice::adaptive;     ///< stage 0
  PassChoice sixteenths = PassChoice::adaptive;    ///< stage 3's sixteenths (stage 4 runs only with them)
  PassChoice proximity = PassChoice::adaptive;     ///< stage 4
  PassChoice orphan_carry = PassChoice::adaptive;  ///< the candidates carry the orphans
  PassChoice certificates = PassChoice::adaptive;  ///< orphan blocks skipped by their certificates
  /// Every rule forced one way: the work each step counts is then the same for every schedule and run.
  [[nodiscard]] static StageRuleChoices all(PassChoice c) { return {c, c, c, c, c}; }
  bool operator==(const StageRuleChoices&) const = default;
};
/// narrow.rules's keys, each with its member: the one list the YAML reader and writer go through.
[[nodiscard]] inline std::array<std::pair<const char*, PassChoice*>, 5> stage_rule_settings(StageRuleChoices& c) {
  return {{{"triangles", &c.triangles}, {"sixteenths", &c.sixteenths}, {"proximity", &c.proximity},
           {"orphan_carry", &c.orphan_carry}, {"certificates", &c.certificates}}};
}

/// The one calendar: a period of kPeriod steps, in which each rule has its slot. Slot 0 re-measures the culling
/// passes that do not run (they decide again in steps 0 and 1); each A/B rule runs its other choice in its slot,
/// between clean steps (its reference), the rules that can move a step most first: the end boxes (the
/// traversal and every candidate), stage 0, the orphan carry (the whole orphan loop; after stage 0, because
/// every candidate stage 0 keeps carries its orphans, so stage 0's choice sets what carrying costs), the
/// certificates. The step before the end boxes' slot runs them too, unmeasured, so that the measured one finds
/// their arrays warm (as the certificates' needs the budgets to skip by).
struct RuleCalendar {
  static constexpr std::uint64_t kPeriod = 16;
  static constexpr std::uint64_t kMaxPeriods = 8;  ///< longest interval between re-measurements, in periods
  enum Slot : std::uint64_t { passes = 0, end_boxes_ready = 2, end_boxes = 3, triangles = 5, carry = 7, certificates_ready = 9, certificates = 10 };
  /// Whether `step` is `slot` of a period that a rule re-measuring every `periods` periods measures in.
  [[nodiscard]] static bool at(std::uint64_t step, Slot slot, std::uint64_t periods) {
    return step % kPeriod == slot && (step / kPeriod) % periods == 0;
  }
};

/// A culling pass worth its own cost: it runs while, in the last step it ran, the pairs it removed — priced at
/// that step's measured thread-ns per elementary test — cost more than its own measured thread-ns.
class CullPassRule {
 public:
  explicit CullPassRule(PassChoice choice = PassChoice::adaptive) : choice_(choice) {}
  [[nodiscard]] bool runs(std::uint64_t step) const;
  /// Whether it runs only to be measured again in `step` (adaptive, and it did not pay when last measured).
  [[nodiscard]] bool remeasures(std::uint64_t step) const { return choice_ == PassChoice::adaptive && !pays_ && runs(step); }
  /// What the pass saved in a step it ran, net of its own cost, in thread-ns (negative: it cost more).
  [[nodiscard]] static double net_saving(double own_ns, std::uint64_t removed, double ns_per_test) {
    return double(removed) * ns_per_test - own_ns;
  }
  /// A step's net saving (net_saving plus what the passes that need this one saved), when the pass ran.
  void record(double net);
  /// Another rule switched: a pass that does not pay is measured again at the next `passes` slot.
  void remeasure_soon() { periods_ = 1; }

 private:
  PassChoice choice_;
  bool pays_ = true;
  std::uint64_t periods_ = 1;
};

/// A choice measured against its alternative (stage 0, orphan carry, certificates, end boxes).
class SwitchRule {
 public:
  SwitchRule(PassChoice choice, bool initial, RuleCalendar::Slot slot) : choice_(choice), chosen_(initial), slot_(slot) {}
  /// Whether step `step` runs the alternative of the current choice (never when forced).
  [[nodiscard]] bool measures(std::uint64_t step) const {
    return choice_ == PassChoice::adaptive && RuleCalendar::at(step, slot_, periods_);
  }
  /// Whether the pass runs in `step`.
  [[nodiscard]] bool runs(std::uint64_t step) const {
    if (choice_ != PassChoice::adaptive) return choice_ == PassChoice::on;
    return chosen_ != measures(step);
  }
  [[nodiscard]] bool chosen() const { return chosen_; }
  /// A step that ran the alternative cost `cost`; it is judged against a clean step whose passes were those of
  /// this one but for this rule's (`reference_signature`, StepPlan::signature, on the bits of `mask`): the last
  /// one before, or the first one after (another rule's choice may have changed in between).
  void measured(double cost, unsigned reference_signature, unsigned mask = ~0u);
  /// A clean step: if a measurement waits for a reference of this signature, the rule decides.
  void reference(double cost, unsigned signature);
  /// Another rule switched: the alternative is measured again at the rule's next slot.
  void remeasure_soon() { periods_ = 1; }

 private:
  PassChoice choice_;
  bool chosen_;
  RuleCalendar::Slot slot_;
  std::uint64_t periods_ = 1;
  double pending_cost_ = -1;  ///< the measured alternative waiting for its reference (< 0: none)
  unsigned pending_signature_ = 0, pending_mask_ = ~0u;
};

/// Whether each pass can run at all in a step (a tester's reach, batched mode, orphans to carry …).
struct StepPossible {
  bool triangles = false, culling = false, carry = false, certificates = false, end_boxes = false;
};

/// What one step runs, as the rules decided it (StageRules::plan).
struct StepPlan {
  StepPossible possible;
  bool triangles = false, sixteenths = true, proximity = true, carry = false, certificates = false, end_boxes = false;
  bool clean = true;  ///< every rule runs its choice: the step is the next ones' reference
  /// Which passes run, a bit each: steps are compared only when they differ in the measured rule's bit alone.
  [[nodiscard]] unsigned signature() const {
    return unsigned(triangles) | unsigned(sixteenths) << 1 | unsigned(proximity) << 2 | unsigned(carry) << 3 |
           unsigned(certificates) << 4 | unsigned(end_boxes) << 5;
  }
};

/// The measured costs of a step (StageRules::record): the narrow phase's thread-ns (its stages, the tests, the
/// orphans' motion pass), and the step's own time without its build, for the end boxes (which change the refit and
/// the traversal too).
struct StepCost {
  double narrow_ns = 0;
  double step_ns = 0;
};

/// Every rule of a pipeline, and the reference they are judged against.
class StageRules {
 public:
  StageRules(StageRuleChoices choices, PassChoice end_boxes);

  /// What step `step` runs.
  [[nodiscard]] StepPlan plan(std::uint64_t step, const StepPossible& possible) const;
  /// A step's merged counters and costs, as planned.
  void record(std::uint64_t step, const StepPlan& plan, const NarrowCounters& c, const StepCost& cost);
  /// The narrow phase's measured thread-ns of a step: its stages and tests (NarrowCounters' *_ns).
  [[nodiscard]] static double narrow_ns(const NarrowCounters& c);

 private:
  SwitchRule triangles_, carry_, certificates_, end_boxes_;
  CullPassRule sixteenths_, proximity_;
  StepCost reference_{-1, -1};  ///< the last clean step's costs
  unsigned reference_signature_ = ~0u;  ///< … and the passes it ran
  double ns_per_test_ = -1;     ///< the last measured thread-ns per elementary test
};

}  // namespace ccdlab
