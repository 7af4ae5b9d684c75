#pragma once
// Triangle meshes made in code for generated scenes (framework/sim/sim_scene.hpp): a sheet, a UV sphere, a
// capsule, an open cone frustum (a funnel, or a skirt when widened downwards). Each appends to a MeshData, so
// a scene concatenates its bodies; faces are wound counter-clockwise seen from outside (from +y for a sheet).
#include "framework/mesh/mesh_io.hpp"

namespace ccdlab {

/// A rectangular sheet in the xz-plane at height `centre.y`: size.x × size.y, cells_x × cells_z quads, two
/// triangles each, diagonals alternating (no preferred shear direction). 2·cells_x·cells_z triangles.
void append_sheet(MeshData& m, const Vec3& centre, double size_x, double size_z, int cells_x, int cells_z);

/// A UV sphere: `segments` around and `segments` from pole to pole: 2·segments·(segments − 1) triangles
/// (segments = 20: 760, the paper's Cloth-ball ball).
void append_sphere(MeshData& m, const Vec3& centre, double radius, int segments);

/// A capsule around the segment a–b: a cylinder of `segments` sides and two hemispherical caps.
void append_capsule(MeshData& m, const Vec3& a, const Vec3& b, double radius, int segments);

/// An open cone frustum around the y axis through `centre`: radius r_top at centre.y + height/2, r_bottom at
/// centre.y − height/2; `segments` around, `rows` rings of quads. Funnels, skirts and ruffles.
void append_frustum(MeshData& m, const Vec3& centre, double r_top, double r_bottom, double height, int segments, int rows);

}  // namespace ccdlab
