// ccd_contact: makes the motion of a sub-step free of crossings with ccdlab's own CCD. The sub-step's motion
// x → p runs through a CcdPipeline (self passes when `self` is on and the body allows it; cloth–obstacle passes
// always), with the `float` tester inflated by the cloth thickness, so features that would come closer than the
// thickness are contacts too (the proximity part of the response). Then, in up to `iterations` rounds:
//   each contact, in sorted order, that would end the step closer than a tenth of the thickness (along its
//   normal, velocities taken as constant) gets an inelastic impulse that keeps it that far apart (Bridson,
//   Fedkiw & Anderson 2002, velocity filtering); positions p = x + dt·v are updated and the CCD runs again,
//   until no contact needs an impulse.
// Then the fail-safe: the motion runs through a second pipeline with zero thickness — any contact there is a
// true touch or crossing — and the free vertices of each stop where they were at t (against free cloth), move
// rigidly with the obstacle they touch, or move with the pinned vertices they touch, until none is left; when
// contacts keep cascading (half the rounds), the whole free cloth stops for the sub-step (`global_stops`). The
// frame at t was free of crossings, so all of these are safe; what is left after 16 rounds is counted
// (`unresolved`), never hidden.
#include <algorithm>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/effects/effects.hpp"
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
    // Fail-safe: the motion is checked with zero thickness — any contact now is a true touch or crossing. The
    // free vertices of a contact with the cloth stop where they were at t; those of a contact with an obstacle
    // are carried by the obstacle's own motion over the sub-step (stopping cannot help against a moving
    // obstacle). Until none is left.
    std::size_t left = 0;
    for (int round = 0; round < kFailSafeRounds; ++round) {
      const StepResult r = detect(s, *crossing_);
      left = r.contacts.size();
      if (left == 0) break;
      if (round == kFailSafeRounds / 2) {
        // Contacts keep cascading (heavy gathering): the whole free cloth stops for this sub-step; only what
        // scripted motion carries still moves, and the rounds below resolve contacts against it.
        for (std::size_t i = 0; i < s.p.size(); ++i)
          if (setup.inv_mass[i] > 0) s.p[i] = s.x[i], s.v[i] = Vec3::Zero();
        ++global_stops_;
        continue;
      }
      for (const Contact& c : r.contacts) {
        // What the free vertices of the contact must follow: an obstacle's rigid motion, else the mean
        // displacement of the contact's scripted vertices (pins, handles), else nothing (they stop).
        int obstacle = -1, scripted = 0;
        Vec3 shift = Vec3::Zero();
        for (Index v : c.vertices) {
          const auto i = std::size_t(v);
          if (setup.inv_mass[i] > 0) continue;
          if (i < setup.follows.size() && setup.follows[i] >= 0) obstacle = setup.follows[i];
          shift += s.p[i] - s.x[i], ++scripted;
        }
        Eigen::Isometry3d carry = Eigen::Isometry3d::Identity();
        if (obstacle >= 0) {
          const RigidMotion& m = setup.obstacles[std::size_t(obstacle)].motion;
          carry = m.at(s.time + dt) * m.at(s.time).inverse();
        } else if (scripted > 0) {
          carry.translate(shift / scripted);
        }
        for (Index v : c.vertices) {
          const auto i = std::size_t(v);
          if (setup.inv_mass[i] == 0) continue;
          s.p[i] = carry * s.x[i];
          s.v[i] = (s.p[i] - s.x[i]) / dt;
        }
      }
      stopped_ += left;
    }
    unresolved_ += left;
    return resolved;
  }

  [[nodiscard]] nlohmann::json stats() const override {
    return {{"ccd_steps", ccd_steps_}, {"self_passes", self_passes_}, {"obstacle_passes", obstacle_passes_},
            {"failsafe_contacts", stopped_}, {"global_stops", global_stops_}, {"unresolved", unresolved_}};
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

  static constexpr int kFailSafeRounds = 16;
  Params p_;
  std::unique_ptr<CcdPipeline> pipeline_;  ///< thickness-inflated: contacts to respond to
  std::unique_ptr<CcdPipeline> crossing_;  ///< zero thickness: true touches and crossings (the fail-safe)
  std::uint64_t unresolved_ = 0;   ///< contacts left after the fail-safe, summed over sub-steps
  std::uint64_t stopped_ = 0, ccd_steps_ = 0, self_passes_ = 0, obstacle_passes_ = 0, global_stops_ = 0;
  /// One CCD step x → p, counting the passes it ran (the proof that a scene without self-contact runs none).
  StepResult detect(const SimState& s) { return detect(s, *pipeline_); }
  StepResult detect(const SimState& s, CcdPipeline& pipeline) {
    ++ccd_steps_;
    for (const TraversalPass& pass : pipeline.passes()) ++(pass.self ? self_passes_ : obstacle_passes_);
    return pipeline.step(s.x, s.p);
  }
};

}  // namespace

std::unique_ptr<Effect> make_ccd_contact(const ParamValues& p) {
  return std::make_unique<CcdContact>(
      CcdContact::Params{p.boolean("self"), int(p.integer("iterations")), int(p.integer("k")), p.string("scheduler")});
}

}  // namespace ccdlab
