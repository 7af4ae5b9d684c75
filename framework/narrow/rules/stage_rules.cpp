#include "framework/narrow/rules/stage_rules.hpp"

#include <algorithm>
#include <array>

namespace ccdlab {

bool CullPassRule::runs(std::uint64_t step) const {
  if (choice_ != PassChoice::adaptive) return choice_ == PassChoice::on;
  return pays_ || RuleCalendar::at(step, RuleCalendar::passes, periods_);
}

namespace {
/// The next interval, in periods, of a rule that re-measured: a confirmed choice waits four times longer (up to
/// kMaxPeriods), a switched one is checked again two periods on. Measuring steps are steps on the worse choice:
/// on a 40-step replay, three rounds of them would be half the steps.
std::uint64_t next_periods(std::uint64_t periods, bool switched) {
  return switched ? 2 : std::min(4 * periods, RuleCalendar::kMaxPeriods);
}
}  // namespace

void CullPassRule::record(double net) {
  const bool pays = net > 0;
  periods_ = next_periods(periods_, pays != pays_);
  pays_ = pays;
}

void SwitchRule::measured(double cost, unsigned reference_signature, unsigned mask) {
  pending_cost_ = cost;
  pending_signature_ = reference_signature & mask;
  pending_mask_ = mask;
}

void SwitchRule::reference(double cost, unsigned signature) {
  if (pending_cost_ < 0 || (signature & pending_mask_) != pending_signature_) return;
  const bool switched = pending_cost_ < cost;
  if (switched) chosen_ = !chosen_;
  periods_ = next_periods(periods_, switched);
  pending_cost_ = -1;
}

StageRules::StageRules(StageRuleChoices choices, PassChoice end_boxes)
    : triangles_(choices.triangles, true, RuleCalendar::triangles),
      carry_(choices.orphan_carry, false, RuleCalendar::carry),
      certificates_(choices.certificates, true, RuleCalendar::certificates),
      end_boxes_(end_boxes, false, RuleCalendar::end_boxes),
      sixteenths_(choices.sixteenths),
      proximity_(choices.proximity) {}

StepPlan StageRules::plan(std::uint64_t step, const StepPossible& can) const {
  StepPlan p;
  p.possible = can;
  p.triangles = can.triangles && triangles_.runs(step);
  p.sixteenths = can.culling && sixteenths_.runs(step);
  p.proximity = p.sixteenths && proximity_.runs(step);  // stage 4 works on the sixteenths' windows
  p.carry = can.carry && carry_.runs(step);
  // Certificates skip a block only from the last step's budgets: the step before their measuring slot sets them.
  const bool readies = can.certificates && !certificates_.chosen() && certificates_.measures(step + 1);
  p.certificates = can.certificates && !p.carry && (certificates_.runs(step) || readies);
  const bool warms = can.end_boxes && end_boxes_.measures(step + 1);  // the step before the measured one
  p.end_boxes = can.end_boxes && (warms ? !end_boxes_.chosen() : end_boxes_.runs(step));
  const bool remeasures = (p.sixteenths && sixteenths_.remeasures(step)) || (p.proximity && proximity_.remeasures(step));
  p.clean = !(can.triangles && triangles_.measures(step)) && !(can.carry && carry_.measures(step)) &&
            !(can.certificates && !p.carry && certificates_.measures(step)) && !readies &&
            !(can.end_boxes && end_boxes_.measures(step)) && !warms && !remeasures;
  return p;
}

double StageRules::narrow_ns(const NarrowCounters& c) {
  return double(c.triangle_ns + c.gather_ns + c.kdop_ns + c.plane_ns + c.split_ns + c.sixteenths_ns + c.proximity_ns +
                c.test_ns + c.orphan_motion_ns);
}

void StageRules::record(std::uint64_t step, const StepPlan& plan, const NarrowCounters& c, const StepCost& cost) {
  const auto choices = [&] {
    return std::array{triangles_.chosen(), carry_.chosen(), certificates_.chosen(), end_boxes_.chosen()};
  };
  const auto before = choices();
  // The culling passes, from their own step: each removed pair would have been tested.
  if (const std::uint64_t tests = c.vf_tests + c.ee_tests; tests > 0) ns_per_test_ = double(c.test_ns) / double(tests);
  if (ns_per_test_ >= 0) {
    double later = 0;
    if (plan.proximity && c.proximity_tested > 0) {
      const double net = CullPassRule::net_saving(double(c.proximity_ns), c.proximity_culled, ns_per_test_);
      proximity_.record(net);
      later = std::max(0.0, net);
    }
    if (plan.sixteenths && c.sixteenths_tested > 0)
      sixteenths_.record(CullPassRule::net_saving(double(c.sixteenths_ns), c.sixteenths_culled, ns_per_test_) + later);
  }
  // The A/B rules, against the last clean step before, or the first after, that ran the same passes but theirs.
  const StepPossible& can = plan.possible;
  const unsigned signature = plan.signature();
  const auto alternative = [&](SwitchRule& rule, unsigned bit, double measured, double reference, unsigned mask = ~0u) {
    rule.measured(measured, signature ^ bit, mask);
    if (reference >= 0) rule.reference(reference, reference_signature_);
  };
  if (can.triangles && triangles_.measures(step)) alternative(triangles_, 1u, cost.narrow_ns, reference_.narrow_ns);
  if (can.carry && carry_.measures(step))  // carrying, the orphan loop uses no certificates: their bit goes with it
    alternative(carry_, 1u << 3, cost.narrow_ns, reference_.narrow_ns, ~(1u << 4));
  if (can.certificates && !plan.carry && certificates_.measures(step))
    alternative(certificates_, 1u << 4, cost.narrow_ns, reference_.narrow_ns);
  if (can.end_boxes && end_boxes_.measures(step)) alternative(end_boxes_, 1u << 5, cost.step_ns, reference_.step_ns);
  if (plan.clean) {
    for (SwitchRule* rule : {&triangles_, &carry_, &certificates_}) rule->reference(cost.narrow_ns, signature);
    end_boxes_.reference(cost.step_ns, signature);
    reference_ = cost;
    reference_signature_ = signature;
  }
  // An A/B switch leaves every other choice measured under the old combination: measured again at their next
  // slots (the switched rule keeps its own interval). The culling passes' own decisions, taken every step they
  // run, trigger nothing: step-to-step noise would keep every rule measuring.
  const auto after = choices();
  if (after == before) return;
  SwitchRule* const switches[] = {&triangles_, &carry_, &certificates_, &end_boxes_};
  for (std::size_t i = 0; i < std::size(switches); ++i)
    if (after[i] == before[i]) switches[i]->remeasure_soon();
  sixteenths_.remeasure_soon();
  proximity_.remeasure_soon();
}

}  // namespace ccdlab
