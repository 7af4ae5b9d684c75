#pragma once
// `drape_fold`: the built-in kinematic scene (no data needed). A square cloth sheet, [-1, 1]² in material
// coordinates, is animated by prescribed motion — no physics (the simulator is a later issue):
//   1. wrinkles : small sinusoidal waves across the sheet (amplitude `wrinkle`; 0 = off)
//   2. fold     : the part right of the crease wraps around a thin cylinder (radius `crease_radius`) and
//                 turns over by an angle growing smoothly from 0 to `fold_deg`. Past 180° the flap folds
//                 THROUGH the lower half, so later steps have heavy self-contact along a moving line.
//   3. drape    : a sphere (radius `sphere_radius`; 0 = no sphere) travels along x under the sheet, which
//                 rests on it with a small gap; the sphere is a second body (an obstacle).
// Only the effects with non-zero parameters are computed. Triangles: 2·resolution² (+ sphere).
#include "framework/scene/mesh_sequence.hpp"

namespace ccdlab {

struct DrapeFoldParams {
  int resolution = 104;          ///< grid cells per side of the sheet
  int frames = 24;               ///< frames (steps = frames − 1)
  double fold_deg = 200;         ///< final fold angle in degrees (0 = no fold)
  double crease = -0.1;          ///< crease position in material x ∈ (−1, 1)
  double crease_radius = 0.03;   ///< radius of the fold's round crease
  double wrinkle = 0.01;         ///< wrinkle amplitude (0 = flat)
  double sphere_radius = 0.5;    ///< 0 = no sphere
  int sphere_segments = 32;      ///< sphere tessellation (longitude segments; latitude = half)
  double sphere_travel = 0.5;    ///< the sphere moves from x = −travel to +travel
  bool self_collision = true;
};

MeshSequence make_drape_fold_scene(const DrapeFoldParams& p);

}  // namespace ccdlab
