// pin: fixes the cloth vertices whose rest position lies in a box (min_x … max_z), or moves them as a
// scripted handle: at velocity (vx, vy, vz) between move_start and move_end, or rigidly with an obstacle
// (`follow: NAME` — a waistband sewn to a moving body). Pinned vertices get zero inverse mass, so no
// constraint or collision moves them.
#include <algorithm>

#include "framework/util/error.hpp"
#include "strategies/effects/effects.hpp"

namespace ccdlab {
namespace {

class Pin final : public Effect {
 public:
  using Params = PinParams;
  explicit Pin(Params p) : p_(p) {}
  [[nodiscard]] std::string_view name() const override { return "pin"; }
  [[nodiscard]] Stage stage() const override { return Stage::constraint; }
  [[nodiscard]] std::string_view work_name() const override { return "pinned vertices placed"; }
  void setup(SimSetup& setup) override {
    for (Index v : setup.cloth_vertices()) {
      const Vec3& r = setup.rest[std::size_t(v)];
      if ((r.array() >= p_.lo.array()).all() && (r.array() <= p_.hi.array()).all()) {
        pinned_.push_back(v);
        setup.inv_mass[std::size_t(v)] = 0;
      }
    }
    if (!p_.follow.empty()) {
      for (std::size_t o = 0; o < setup.obstacles.size(); ++o)
        if (setup.obstacles[o].name == p_.follow) follow_ = int(o);
      if (follow_ < 0) fail("effects: pin: follow: no obstacle is named '{}'", p_.follow);
      if (setup.follows.size() == setup.rest.size())
        for (Index v : pinned_) setup.follows[std::size_t(v)] = follow_;
    }
    if (pinned_.empty())
      fail("effects: pin: no cloth vertex has its rest position in the box [{}, {}, {}] – [{}, {}, {}]", p_.lo.x(),
           p_.lo.y(), p_.lo.z(), p_.hi.x(), p_.hi.y(), p_.hi.z());
  }
  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override {
    if (s.iteration > 0) return 0;
    if (follow_ >= 0) {
      const Eigen::Isometry3d pose = setup.obstacles[std::size_t(follow_)].motion.at(s.time + dt);
      for (Index v : pinned_) s.p[std::size_t(v)] = pose * setup.rest[std::size_t(v)];
      return pinned_.size();
    }
    if (p_.velocity.squaredNorm() == 0) return 0;  // still pins: inv_mass 0 holds them
    const Vec3 offset = p_.velocity * (std::clamp(s.time + dt, p_.move_start, p_.move_end) - p_.move_start);
    for (Index v : pinned_) s.p[std::size_t(v)] = setup.rest[std::size_t(v)] + offset;
    return pinned_.size();
  }

 private:
  Params p_;
  std::vector<Index> pinned_;
  int follow_ = -1;
};

}  // namespace

std::unique_ptr<Effect> make_pin(const ParamValues& p) {
  return std::make_unique<Pin>(Pin::Params{Vec3(p.real("min_x"), p.real("min_y"), p.real("min_z")),
                                           Vec3(p.real("max_x"), p.real("max_y"), p.real("max_z")),
                                           Vec3(p.real("vx"), p.real("vy"), p.real("vz")), p.real("move_start"),
                                           p.real("move_end"), p.string("follow")});
}

}  // namespace ccdlab
