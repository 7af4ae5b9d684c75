// damping: velocities of free vertices decay as exp(−rate · t) (air drag, internal friction, in one number).
#include <cmath>

#include "strategies/effects/effects.hpp"

namespace ccdlab {
namespace {

class Damping final : public Effect {
 public:
  explicit Damping(double rate) : rate_(rate) {}
  [[nodiscard]] std::string_view name() const override { return "damping"; }
  [[nodiscard]] Stage stage() const override { return Stage::force; }
  [[nodiscard]] std::string_view work_name() const override { return "vertices"; }
  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override {
    const double keep = std::exp(-rate_ * dt);
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < s.v.size(); ++i)
      if (setup.inv_mass[i] > 0) s.v[i] *= keep, ++n;
    return n;
  }

 private:
  double rate_;
};

}  // namespace

std::unique_ptr<Effect> make_damping(const ParamValues& p) { return std::make_unique<Damping>(p.real("rate")); }

}  // namespace ccdlab
