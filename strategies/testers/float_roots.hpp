#pragma once
// The `float` tester's root search for many queries at once, and the distance check at the roots it finds
// (SIMD, Highway with run-time dispatch).
//
// FloatTester (float_tester.hpp) looks for the earliest root in [0, 1] of the coplanarity cubic
// f(t) = A(t)·(B(t)×C(t)): the coefficients, the Bernstein early out, the breakpoints (roots of f′), f at each,
// then Illinois false position on the first interval where f changes sign. This kernel does exactly that for a
// block of queries, one per lane, with the same operations in the same order as the scalar code (no fused
// multiply-adds: both files are compiled with -ffp-contract=off), so a lane's root is the scalar tester's root
// bit for bit. It answers only what it can decide that way; the rest goes back to the scalar tester:
//   - none:   f has no root and no touching point in [0, 1] — no contact (thickness 0; with thickness, t = 1
//             is the only candidate left);
//   - root:   `t` is the first candidate time — a breakpoint where f touches zero (|f| within the tolerance), or
//             else the refined root of the first sign change —; the caller checks the distance there. When
//             `more` is set, later candidates exist and a miss at `t` is not the answer (`skip` asks for them);
//   - coplanar: f ≡ 0 (every coefficient within 10⁻¹² of f_scale, all finite): coplanar motion, whose candidate
//               times are crossings in the plane (coplanar_times below);
//   - scalar: anything else (non-finite coefficients, a root of f′ at ±0).
// With thickness > 0 the ends of the step are candidates too, t = 0 before the kernel's and t = 1 after: the
// caller checks the distance at t = 0 first (vertex_faces_at / edge_edges_at below) and at t = 1 where the
// kernel's candidates end without a hit.
#include <cstddef>
#include <cstdint>

namespace ccdlab {

enum class FirstRoot : std::uint8_t { none, root, scalar, coplanar };

/// The root refinement, scalar and batched alike: Illinois false position until the bracket is at most
/// kIllinoisWidth wide, at most kIllinoisSteps steps, never evaluating f closer than kIllinoisGuard to an end of
/// the bracket. Where one end's f is at rounding level the secant lands on that end, and without the guard the
/// bracket would shrink by bisection only; with it, one evaluation beside that end closes the bracket (the root
/// lies within the guard) or moves the end by the guard.
inline constexpr double kIllinoisWidth = 1e-15;
inline constexpr int kIllinoisSteps = 100;
inline constexpr double kIllinoisGuard = 0.4e-15;
static_assert(2 * kIllinoisGuard < kIllinoisWidth, "the guarded point must lie inside every bracket still refined");

/// One block of queries in columns: column k of row i at columns[k·stride + i], for rows [0, n).
struct CubicColumns {
  /// The motion relative to the query's origin: A(t) = A0 + t·dA, and so on; f_scale = L³ (FloatTester).
  enum : int { A0x, A0y, A0z, dAx, dAy, dAz, B0x, B0y, B0z, dBx, dBy, dBz, C0x, C0y, C0z, dCx, dCy, dCz, f_scale, count };
};

/// kind[i], t[i] and more[i] for rows [0, n) of the block; `rel_tolerance` as FloatTester's. With `skip`, row i's
/// candidate is its event number skip[i] in the scalar tester's order (0, the default: the first), so that a caller
/// whose candidate missed with `more` set asks for the next one. The columns must be readable up to a multiple of 8
/// rows past n (the padding's answers are written and meaningless).
void first_coplanar_roots(const double* columns, std::size_t stride, std::size_t n, double rel_tolerance,
                          FirstRoot* kind, double* t, std::uint8_t* more, const std::uint8_t* skip = nullptr);

/// The proximity check at one time per row, for a block: the query's four points P0…P3 moving linearly
/// (Pk(t) = Pk + t·dPk, relative to one origin as the scalar tester's), the time t and the reach. VF: P0 is the
/// vertex, P1–P3 the face (closest_point_triangle); EE: P0P1 against P2P3 (closest_segment_segment).
struct PointColumns {
  enum : int {
    P0x, P0y, P0z, dP0x, dP0y, dP0z, P1x, P1y, P1z, dP1x, dP1y, dP1z,
    P2x, P2y, P2z, dP2x, dP2y, dP2z, P3x, P3y, P3z, dP3x, dP3y, dP3z, t, reach, extent, count
  };
};

/// Which features the four points are: the vertex then the face, or edge P0P1 then edge P2P3.
enum class PointPairing : std::uint8_t { vertex_face, edge_edge };

/// The cubic's columns (CubicColumns) of rows [0, n) from their points' (PointColumns, `extent` the query's L):
/// VF A = P0 − P1, B = P2 − P1, C = P3 − P1; EE A = P2 − P0, B = P1 − P0, C = P3 − P2, position and motion
/// apart, as FloatTester forms them; f_scale = L³. Both sets of columns have the same stride; readable and
/// writable up to a multiple of 8 rows past n.
void cubic_columns(const double* points, std::size_t stride, std::size_t n, PointPairing pairing, double* cubic);

/// Coplanar motion (FirstRoot::coplanar): FloatTester's candidate times for rows [0, n) of the points' columns —
/// t = 0, t = 1, and at each end's plane normal the times where a point crosses a line of the other feature (VF:
/// the vertex and each face edge; EE: each endpoint and the other edge) — one slot per column of `times` (the
/// points' stride; +∞ where a slot holds no time in [0, 1]), bit for bit the scalar tester's times. scalar[i] is
/// set where the row is left to the scalar tester: its four points collinear at an end (no plane normal), or a
/// crossing at t = ±0, whose place beside t = 0 in the scalar tester's sort the kernel does not mirror.
inline constexpr int kCoplanarSlots = 18;  // 2 ends + 2 plane normals × 4 point–line pairs × 2 roots (EE)
void coplanar_times(const double* points, std::size_t stride, std::size_t n, PointPairing pairing, double* times,
                    std::uint8_t* scalar);

/// A row's answer at its time: within reach (`hit`, with the contact's coordinates), not (`miss`), or a case the
/// kernel leaves to the scalar function (a degenerate triangle, a point-like edge, a NaN).
enum class AtTime : std::uint8_t { miss, hit, scalar };

/// verdict[i] and, on a hit, coords[2i], coords[2i + 1] (CcdHit::coords) for rows [0, n): the scalar functions'
/// distance and coordinates bit for bit (same operations, same order, no fused multiply-adds), compared as
/// `distance² ≤ reach²`. Columns readable up to a multiple of 8 rows past n, as above.
void vertex_faces_at(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords);
void edge_edges_at(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords);

}  // namespace ccdlab
