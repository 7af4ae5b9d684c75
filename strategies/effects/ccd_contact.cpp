// ccd_contact: makes the motion of a sub-step free of crossings with ccdlab's own CCD. The sub-step's motion
// x → p runs through a CcdPipeline (self passes when `self` is on and the body allows it; cloth–obstacle passes
// always), with the `float` tester inflated by the cloth thickness, so features that would come closer than the
// thickness are contacts too (the proximity part of the response). Then, in up to `iterations` rounds:
//   each contact, in sorted order, that would end the step closer than a tenth of the thickness (along its
//   normal, velocities taken as constant) gets an inelastic impulse that keeps it that far apart (Bridson,
//   Fedkiw & Anderson 2002, velocity filtering); positions p = x + dt·v are updated and the CCD runs again,
//   until no contact needs an impulse.
// Then the motion runs through a second pipeline with zero thickness — any contact there is a true touch or
// crossing — and every such contact becomes a constraint of an inelastic projection (inelastic_projection.hpp,
// Harmon et al. 2008), which treats them all at once: cloth held by two obstacles that move differently (a
// knee) is pushed out of both. What it leaves after kProjectionRounds goes to the last resort, rigid impact
// zones (impact_zones.hpp): the vertices of each contact join a zone that moves rigidly (with its momentum, or
// with the scripted motion it holds), round after round until none is left. The frame at t was free of
// crossings and rigid motion keeps it so; what is left (pinched zones, or the round bound) is counted
// (`unresolved`), never hidden.
#include <algorithm>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/effects/effects.hpp"
#include "strategies/effects/impact_zones.hpp"
#include "strategies/effects/inelastic_projection.hpp"
#include "strategies/registry.hpp"

namespace ccdlab {
namespace {

class CcdContact final : public Effect {
 public:
  using Params = CcdContactParams;
  explicit CcdContact(Params p) : p_(std::move(p)) {}
  [[nodiscard]] std::string_view name() const override { return "ccd_contact"; }
  [[nodiscard]] Stage stage() const override { return Stage::collision; }
  [[nodiscard]] std::string_view work_name() const override { return "contacts resolved"; }

  void setup(SimSetup& setup) override {
    std::vector<Body> bodies = setup.bodies;
    for (Body& b : bodies) b.self_collision = b.self_collision && p_.self;
    auto make = [&](double thickness) {
      PipelineStrategies s = contact_strategies(p_.k, p_.scheduler, setup.threads, thickness);
      s.restructure_threshold = 2.0;  // cloth deforms far from its rest shape: rebuild sub-trees that degrade
      return std::make_unique<CcdPipeline>(*setup.mesh, bodies, std::move(s));
    };
    pipeline_ = make(setup.thickness);
    crossing_ = make(0);
  }

  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override {
    std::uint64_t resolved = 0;
    for (int round = 0; round < p_.iterations; ++round) {
      const StepResult r = detect(s);
      std::uint64_t applied = 0;
      for (const Contact& c : r.contacts) applied += respond(setup, s, c, dt);
      if (applied == 0) break;  // every contact already ends the step far enough apart
      resolved += applied;
      for (std::size_t i = 0; i < s.p.size(); ++i)
        if (setup.inv_mass[i] > 0) s.p[i] = s.x[i] + dt * s.v[i];
    }
    // The motion checked with zero thickness — any contact there is a true touch or crossing: first every such
    // contact at once, by inelastic projection (inelastic_projection.hpp); what that leaves, by rigid impact
    // zones (impact_zones.hpp), until none is left or no round can merge anything new.
    const InelasticProjection::Outcome projected =
        projection_.resolve(*crossing_, setup, s, dt, gap(setup), kProjectionRounds);
    count_passes(*crossing_, projected.detections);
    if (projected.left.empty()) return resolved;
    const ImpactZones::Outcome zoned = zones_.resolve(*crossing_, setup, s, dt, kZoneRounds, &projected.left);
    count_passes(*crossing_, zoned.detections);
    zone_contacts_ += zoned.handled;
    unresolved_ += zoned.left;
    return resolved;
  }

  [[nodiscard]] nlohmann::json stats() const override {
    return {{"ccd_steps", ccd_steps_},
            {"self_passes", self_passes_},
            {"obstacle_passes", obstacle_passes_},
            {"projection_rows", projection_.rows},
            {"projection_solves", projection_.solves},
            {"projection_sweeps", projection_.sweeps},
            {"projection_unconverged", projection_.unconverged},
            {"projection_resolved", projection_.resolved},
            {"zone_contacts", zone_contacts_},
            {"zones_moved", zones_.zones_moved},
            {"largest_zone", zones_.largest_zone},
            {"most_rounds", zones_.most_rounds},
            {"escalated", zones_.escalated},
            {"whole_bodies", zones_.whole_bodies},
            {"pinched_zones", zones_.pinched_zones},
            {"unresolved", unresolved_}};
  }

 private:
  /// One contact's impulse, if it needs one (returns 1 if it did): the contact's row (inelastic_projection.hpp)
  /// asks the features to end the step a tenth of the thickness apart along its normal.
  std::uint64_t respond(const SimSetup& setup, SimState& s, const Contact& c, double dt) const {
    const ContactRow row = contact_row(c, setup, s, dt, gap(setup));
    if (row.n.squaredNorm() == 0 || row.mass == 0) return 0;
    const double vn = row.normal_velocity(s.v);
    if (vn >= row.target) return 0;
    row.apply(setup, s.v, (row.target - vn) / row.mass);
    return 1;
  }
  /// The separation every response aims for: a tenth of the thickness (so that the next sub-step's inflated
  /// CCD still sees the pair, and its impulse keeps it there).
  static double gap(const SimSetup& setup) { return 0.1 * std::max(setup.thickness, 1e-9); }

  static constexpr int kProjectionRounds = 8;  ///< solves before the zones take over
  static constexpr int kZoneRounds = 64;       ///< zones only grow: a bound, seldom reached
  Params p_;
  std::unique_ptr<CcdPipeline> pipeline_;  ///< thickness-inflated: contacts to respond to
  std::unique_ptr<CcdPipeline> crossing_;  ///< zero thickness: true touches and crossings (impact zones)
  InelasticProjection projection_;
  ImpactZones zones_;
  std::uint64_t unresolved_ = 0;     ///< contacts left after the impact zones, summed over sub-steps
  std::uint64_t zone_contacts_ = 0;  ///< contacts handed to the impact zones, summed over rounds
  std::uint64_t ccd_steps_ = 0, self_passes_ = 0, obstacle_passes_ = 0;
  /// One CCD step x → p, counting the passes it ran (the proof that a scene without self-contact runs none).
  StepResult detect(const SimState& s) {
    count_passes(*pipeline_, 1);
    return pipeline_->step(s.x, s.p);
  }
  void count_passes(const CcdPipeline& pipeline, int steps) {
    ccd_steps_ += std::uint64_t(steps);
    for (const TraversalPass& pass : pipeline.passes()) (pass.self ? self_passes_ : obstacle_passes_) += std::uint64_t(steps);
  }
};

}  // namespace

std::unique_ptr<Effect> make_ccd_contact(const ParamValues& p) {
  const long long k = p.integer("k");
  if (const std::string expected = setting_check::k(k); !expected.empty())
    fail("effect ccd_contact: k: expected {}, got {}", expected, k);
  return std::make_unique<CcdContact>(
      CcdContact::Params{p.boolean("self"), int(p.integer("iterations")), int(k), p.string("scheduler")});
}

}  // namespace ccdlab
