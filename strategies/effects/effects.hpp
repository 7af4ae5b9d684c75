#pragma once
// Factories of the built-in effects (strategies/registry.cpp registers them by name with their parameters).
// One effect per file: gravity.cpp, damping.cpp, wind.cpp, stretch.cpp, bend.cpp, pin.cpp,
// obstacle_contact.cpp, ccd_contact.cpp.
#include <memory>

#include "framework/config/registry.hpp"
#include "framework/sim/effect.hpp"

namespace ccdlab {

std::unique_ptr<Effect> make_gravity(const ParamValues& p);
std::unique_ptr<Effect> make_damping(const ParamValues& p);
std::unique_ptr<Effect> make_wind(const ParamValues& p);
std::unique_ptr<Effect> make_stretch(const ParamValues& p);
std::unique_ptr<Effect> make_bend(const ParamValues& p);
std::unique_ptr<Effect> make_pin(const ParamValues& p);
std::unique_ptr<Effect> make_obstacle_contact(const ParamValues& p);
std::unique_ptr<Effect> make_ccd_contact(const ParamValues& p);

}  // namespace ccdlab
