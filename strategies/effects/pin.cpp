// pin: fixes the cloth vertices whose rest position lies in a box (min_x … max_z), or moves them as a
// scripted handle at velocity (vx, vy, vz) between move_start and move_end. Pinned vertices get zero inverse
// mass, so no constraint or collision moves them.
#include <algorithm>

#include "framework/util/error.hpp"
#include "strategies/effects/effects.hpp"

namespace ccdlab {
namespace {

class Pin final : public Effect {
 public:
  struct Params {
    Vec3 lo, hi, velocity;
    double move_start = 0, move_end = 1e300;
  };
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
    if (pinned_.empty())
      fail("effects: pin: no cloth vertex has its rest position in the box [{}, {}, {}] – [{}, {}, {}]", p_.lo.x(),
           p_.lo.y(), p_.lo.z(), p_.hi.x(), p_.hi.y(), p_.hi.z());
  }
  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override {
    if (p_.velocity.squaredNorm() == 0 || s.iteration > 0) return 0;  // still pins: inv_mass 0 holds them
    const Vec3 offset = p_.velocity * (std::clamp(s.time + dt, p_.move_start, p_.move_end) - p_.move_start);
    for (Index v : pinned_) s.p[std::size_t(v)] = setup.rest[std::size_t(v)] + offset;
    return pinned_.size();
  }

 private:
  Params p_;
  std::vector<Index> pinned_;
};

}  // namespace

std::unique_ptr<Effect> make_pin(const ParamValues& p) {
  return std::make_unique<Pin>(Pin::Params{Vec3(p.real("min_x"), p.real("min_y"), p.real("min_z")),
                                           Vec3(p.real("max_x"), p.real("max_y"), p.real("max_z")),
                                           Vec3(p.real("vx"), p.real("vy"), p.real("vz")), p.real("move_start"),
                                           p.real("move_end")});
}

}  // namespace ccdlab
