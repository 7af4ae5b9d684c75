// ccd_contact: makes the motion of a sub-step free of crossings with ccdlab's own CCD. The sub-step's motion
// x → p runs through a CcdPipeline (self passes when `self` is on and the body allows it; cloth–obstacle passes
// always), with the `float` tester inflated by the cloth thickness, so features that would come closer than the
// thickness are contacts too (the proximity part of the response). Then, in up to `iterations` rounds:
//   each contact, in sorted order, that would end the step closer than a tenth of the thickness (along its
//   normal, velocities taken as constant) gets an inelastic impulse that keeps it that far apart (Bridson,
//   Fedkiw & Anderson 2002, velocity filtering); positions p = x + dt·v are updated and the CCD runs again,
//   until no contact needs an impulse.
// Then the last resort, rigid impact zones (impact_zones.hpp): the motion runs through a second pipeline with
// zero thickness — any contact there is a true touch or crossing — and the vertices of each contact join a zone
// that moves rigidly (with its momentum, or with the scripted motion it holds), round after round until none is
// left. The frame at t was free of crossings and rigid motion keeps it so; what is left (pinched zones, or the
// round bound) is counted (`unresolved`), never hidden.
#include <algorithm>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/effects/effects.hpp"
#include "strategies/effects/impact_zones.hpp"
#include "strategies/registry.hpp"

namespace ccdlab {
namespace {

class CcdContact final : public Effect {
 public:
  struct Params {
    bool self = true;
    int iterations = 4;
    int k = 18;
    std::string scheduler = "phc";
  };
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
    // Last resort: rigid impact zones (impact_zones.hpp) on the motion checked with zero thickness — any
    // contact there is a true touch or crossing — until none is left or no round can merge anything new.
    const ImpactZones::Outcome zoned = zones_.resolve(*crossing_, setup, s, dt, kZoneRounds);
    count_passes(*crossing_, zoned.detections);
    zone_contacts_ += zoned.handled;
    unresolved_ += zoned.left;
    return resolved;
  }

  [[nodiscard]] nlohmann::json stats() const override {
    return {{"ccd_steps", ccd_steps_},
            {"self_passes", self_passes_},
            {"obstacle_passes", obstacle_passes_},
            {"zone_contacts", zone_contacts_},
            {"zones_moved", zones_.zones_moved},
            {"largest_zone", zones_.largest_zone},
            {"most_rounds", zones_.most_rounds},
            {"escalated", zones_.escalated},
            {"pinched_zones", zones_.pinched_zones},
            {"unresolved", unresolved_}};
  }

 private:
  /// One contact's impulse. Weights w give the relative position of the features: VF vertex − face point,
  /// EE point on a − point on b; the normal is oriented so that the separation at t is positive.
  /// Applies the contact's impulse if it needs one; returns 1 if it did.
  std::uint64_t respond(const SimSetup& setup, SimState& s, const Contact& c, double dt) const {
    std::array<double, 4> w{};
    const auto [u, t] = c.coords;
    if (c.kind == ContactKind::vf) w = {1, -(1 - u - t), -u, -t};
    else w = {1 - u, u, -(1 - t), -t};
    Vec3 n = contact_normal(c, s.x, s.p);
    if (n.squaredNorm() == 0) return 0;
    double d0 = 0, vn = 0, mass = 0;
    for (int k = 0; k < 4; ++k) {
      const auto i = std::size_t(c.vertices[std::size_t(k)]);
      d0 += w[std::size_t(k)] * s.x[i].dot(n);
      mass += w[std::size_t(k)] * w[std::size_t(k)] * setup.inv_mass[i];
    }
    if (d0 < 0) n = -n, d0 = -d0;
    for (int k = 0; k < 4; ++k) vn += w[std::size_t(k)] * s.v[std::size_t(c.vertices[std::size_t(k)])].dot(n);
    const double target = (0.1 * std::max(setup.thickness, 1e-9) - d0) / dt;  // end the step ≥ thickness/10 apart
    if (vn >= target || mass == 0) return 0;
    const double j = (target - vn) / mass;
    for (int k = 0; k < 4; ++k) {
      const auto i = std::size_t(c.vertices[std::size_t(k)]);
      s.v[i] += j * w[std::size_t(k)] * setup.inv_mass[i] * n;
    }
    return 1;
  }

  static constexpr int kZoneRounds = 64;  ///< zones only grow: a bound, seldom reached
  Params p_;
  std::unique_ptr<CcdPipeline> pipeline_;  ///< thickness-inflated: contacts to respond to
  std::unique_ptr<CcdPipeline> crossing_;  ///< zero thickness: true touches and crossings (impact zones)
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
  return std::make_unique<CcdContact>(
      CcdContact::Params{p.boolean("self"), int(p.integer("iterations")), int(p.integer("k")), p.string("scheduler")});
}

}  // namespace ccdlab
