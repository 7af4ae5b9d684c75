// gravity: a constant acceleration (gx, gy, gz) on every free vertex.
#include "strategies/effects/effects.hpp"

namespace ccdlab {
namespace {

class Gravity final : public Effect {
 public:
  explicit Gravity(Vec3 g) : g_(g) {}
  [[nodiscard]] std::string_view name() const override { return "gravity"; }
  [[nodiscard]] Stage stage() const override { return Stage::force; }
  [[nodiscard]] std::string_view work_name() const override { return "vertices"; }
  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < s.v.size(); ++i)
      if (setup.inv_mass[i] > 0) s.v[i] += dt * g_, ++n;
    return n;
  }

 private:
  Vec3 g_;
};

}  // namespace

std::unique_ptr<Effect> make_gravity(const ParamValues& p) {
  return std::make_unique<Gravity>(Vec3(p.real("gx"), p.real("gy"), p.real("gz")));  // GravityParams
}

}  // namespace ccdlab
