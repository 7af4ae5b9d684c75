#pragma once
// The built-in effects' parameters and factories (strategies/registry.cpp registers them by name, each parameter's
// default read from these Params). One effect per file: gravity.cpp, damping.cpp, wind.cpp, stretch.cpp,
// bend.cpp, pin.cpp, obstacle_contact.cpp, ccd_contact.cpp.
#include <memory>
#include <string>

#include "framework/config/registry.hpp"
#include "framework/geometry/vec.hpp"
#include "framework/pipeline/pipeline_settings.hpp"
#include "framework/sim/effect.hpp"

namespace ccdlab {

struct GravityParams {
  Vec3 g{0, -9.81, 0};  ///< m/s²
};
struct DampingParams {
  double rate = 0.5;  ///< velocities decay as exp(−rate·t), 1/s
};
struct WindParams {
  Vec3 velocity{3, 0, 0};
  double drag = 1.0;
  double turbulence = 0.3;  ///< gust amplitude relative to |velocity|
};
struct StretchParams {
  double compliance = 1e-8;  ///< inverse stiffness, m/N (0 = inextensible)
};
struct BendParams {
  double compliance = 1e-5;
};
struct PinParams {
  Vec3 lo{-1e9, -1e9, -1e9}, hi{1e9, 1e9, 1e9};  ///< the box of rest positions pinned
  Vec3 velocity{0, 0, 0};                        ///< a scripted handle's velocity
  double move_start = 0, move_end = 1e9;         ///< when the handle moves, s
  std::string follow;                            ///< obstacle name, or empty
};
struct ObstacleContactParams {
  double friction = 0.3;  ///< Coulomb coefficient
};
struct CcdContactParams {
  bool self = true;
  int iterations = 4;
  int k = PipelineSettings{}.k;
  std::string scheduler = "phc";
};

std::unique_ptr<Effect> make_gravity(const ParamValues& p);
std::unique_ptr<Effect> make_damping(const ParamValues& p);
std::unique_ptr<Effect> make_wind(const ParamValues& p);
std::unique_ptr<Effect> make_stretch(const ParamValues& p);
std::unique_ptr<Effect> make_bend(const ParamValues& p);
std::unique_ptr<Effect> make_pin(const ParamValues& p);
std::unique_ptr<Effect> make_obstacle_contact(const ParamValues& p);
std::unique_ptr<Effect> make_ccd_contact(const ParamValues& p);

}  // namespace ccdlab
