#pragma once
// ccdlab's C++ API: continuous collision detection between triangles moving linearly over a time step, and the
// pairs closer than a distance at one set of positions (a barrier solver's active set), for one deforming mesh or
// several bodies (cloth and obstacles). Guide and example: docs/embedding.md, docs/proximity.md, examples/.
//
//   ccdlab::Detector detector(faces, ccdlab::Options::from_yaml("scheduler: phc\nthreads: 4"));
//   ccdlab::Detector::Contacts c = detector.step(x0, x1);              // every VF / EE contact of the step
//   ccdlab::Detector::Proximities near = detector.proximity(x, dhat);  // every VF / EE pair closer than dhat
//
// The topology is fixed when the Detector is made; its BVH is built on the first step and refit on every later
// one. The API never prints and never exits the process: every failure is a ccdlab::Error (ccdlab/error.hpp)
// whose message names the call, and the file, line and field where there is one. Only the standard library
// appears here; everything else stays inside the library. (Contact, Contacts and Body are Detector's own
// types: the framework inside has types of those names in namespace ccdlab.)
#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ccdlab/error.hpp"

namespace ccdlab {

using Point = std::array<double, 3>;
using Triangle = std::array<int, 3>;  ///< vertex indices, counter-clockwise seen from the front

/// A mesh as read from one .ply or .obj file (validated: finite coordinates, indices in range).
struct MeshFile {
  std::vector<Point> positions;
  std::vector<Triangle> faces;
};

/// Reads an .obj or .ply file (ascii or binary PLY; polygons fan-triangulated). Throws Error naming the file and
/// the line (text) or element (binary) on any malformed input.
MeshFile read_mesh(const std::filesystem::path& path);

/// How a Detector works: one member per row of the settings table (ccdlab/settings.def — its key, CLI flag and
/// one-line doc there; docs/config.md's table lists them with their defaults). A member left empty keeps the
/// pipeline's default; a set one is checked when a Detector is made, with the messages a YAML file gets
/// ("Options::k: expected one of 6, 14, 18, 26, got 7"). Strategy members take a name or "name:key=value,…"
/// (e.g. tester = "conservative:delta=1e-9"); choice members a name (end_boxes = "off").
///
///   ccdlab::Options o;
///   o.scheduler = "phc", o.threads = 4;
struct Options {
#define CCDLAB_SETTING(kind, member, type, ...) std::optional<type> member;
#include "ccdlab/settings.def"
#undef CCDLAB_SETTING

  /// Options from YAML text with the keys of an experiment's settings (bv {k, width, end_boxes}, hierarchy,
  /// scheduler, threads, tester, narrow {…}, memory_limit, …) and no others; every member is then set, the
  /// defaults filled in. `source` names the text in errors ("<source>:line: key: expected …, got …").
  static Options from_yaml(std::string_view yaml, std::string_view source = "ccdlab::Options::from_yaml");
};

class Detector {
 public:
  /// One body of a scene: its own faces (indices into its own vertices) and vertex count. A cloth is tested against
  /// every body and, with self_collision, against itself; an obstacle only against cloth.
  struct Body {
    std::vector<Triangle> faces;
    int vertices = 0;
    bool obstacle = false;
    bool self_collision = true;
    std::string name;  ///< used in error messages
  };

  /// A contact: the four vertex ids (VF: the vertex, then the face's three; EE: edge a's two, then edge b's), the
  /// earliest time of contact in [0, 1] (a lower bound for `conservative`), the contact's coordinates (VF:
  /// barycentric weights of the face's 2nd and 3rd vertex; EE: parameters along edge a and edge b) and the unit
  /// normal at that time (VF: the face's, (f1 − f0) × (f2 − f0); EE: edge a × edge b; zero where the face is
  /// degenerate or the edges parallel then).
  struct Contact {
    std::array<int, 4> vertices;
    double toi;
    std::array<double, 2> coords;
    Point normal;
  };

  /// A step's contacts, each list in the order of its features' ids: the same lists, in the same order, for every
  /// scheduler and thread count.
  struct Contacts {
    std::vector<Contact> vf;
    std::vector<Contact> ee;
  };

  /// One self-colliding mesh. The vertex count is fixed by the first step (it must cover every face index).
  explicit Detector(std::span<const Triangle> faces, const Options& options = {});
  /// Several bodies; a step's positions are the bodies' vertices one after the other, in this order.
  explicit Detector(std::span<const Body> bodies, const Options& options = {});
  ~Detector();
  Detector(Detector&&) noexcept;
  Detector& operator=(Detector&&) noexcept;

  /// Every contact while each vertex moves linearly from x0 to x1. x0 and x1 hold the same number of finite
  /// positions, the vertex count of the first step.
  [[nodiscard]] Contacts step(std::span<const Point> x0, std::span<const Point> x1);

  /// The earliest time of contact in [0, 1] while each vertex moves linearly from x0 to x1, 1.0 when there is
  /// none: the minimum of step()'s times, found without solving the pairs that cannot beat the best time found
  /// so far. With `conservative` or `exact` it is never later than the true earliest contact, `conservative`
  /// within 1e-9 of it (the hits that can be the earliest are narrowed). For a collision-free step size: move by
  /// a fraction of it.
  [[nodiscard]] double earliest_toi(std::span<const Point> x0, std::span<const Point> x1);

  /// A vertex–face or edge–edge pair closer than d̂: its vertex ids (as a Contact's), its distance, the type of its
  /// closest features — "p_t" (inside the face), "p_e0" / "p_e1" / "p_e2" (edge (f0, f1) / (f1, f2) / (f2, f0)),
  /// "p_t0" / "p_t1" / "p_t2" (a corner); "ea_eb" (inside both edges), "ea0_eb" … "ea_eb1" (an end of one edge),
  /// "ea0_eb0" … "ea1_eb1" (two ends) — and their coordinates (VF: barycentric weights of f1, f2; EE: parameters
  /// along edge a, edge b).
  struct Proximity {
    std::array<int, 4> vertices;
    double distance;
    std::string_view type;  ///< one of the static names above
    std::array<double, 2> coords;
  };
  /// Pairs in the order of their features' ids, the same for every scheduler and thread count.
  struct Proximities {
    std::vector<Proximity> vf;
    std::vector<Proximity> ee;
  };

  /// Every non-adjacent vertex–face and edge–edge pair (of bodies that collide, as for step()) whose exact distance at
  /// positions x is below dhat > 0: none missed, none farther reported (decided exactly; docs/proximity.md). Its
  /// hierarchy is built on the first call with a given dhat and refit on later ones; the queries of the last four
  /// dhat values are kept.
  [[nodiscard]] Proximities proximity(std::span<const Point> x, double dhat);

  /// What a barrier solver's line search asks at each iterate: the active set at x0 (proximity(x0, dhat)) and the
  /// collision-free step size from x0 towards x1 — the largest fraction t of the step such that no pair comes closer
  /// than `separation` while the vertices move linearly to x0 + t (x1 − x0), 1.0 when none does (the earliest time
  /// of `conservative:thickness=separation`: never later than the true one).
  struct ActiveSetAndStep {
    Proximities active;
    double step_size;
  };
  [[nodiscard]] ActiveSetAndStep active_set_and_step(std::span<const Point> x0, std::span<const Point> x1, double dhat,
                                                     double separation);

  /// The options in effect, every default filled in (the resolved strategy parameters as YAML).
  [[nodiscard]] std::string resolved_options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ccdlab
