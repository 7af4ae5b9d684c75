#pragma once
// The scene simulator's unit of physics: an Effect is one physical effect a scene declares (gravity, stretch,
// bending, damping, wind, pins, obstacle contact, self-contact response …). A scene lists its effects; the
// simulator calls only those, so an effect a scene does not list costs nothing — no force, no collision pass.
//
// A sub-step of length dt (framework/sim/simulator.hpp) runs the stages in this order:
//   force       change velocities v of free vertices (gravity, wind, damping)
//   (predict)   p = x + dt·v for free vertices; scripted (kinematic) vertices get their position at t + dt
//   constraint  move predicted positions p, once per solver iteration (XPBD: stretch, bend, pins, colliders)
//   (velocity)  v = (p − x) / dt
//   collision   make the motion x → p free of crossings (CCD-based response); may change p and v
// Effects own their parameters (a Params struct, from YAML through the effect registry) and their counters.
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/pipeline/bodies.hpp"
#include "framework/sim/rigid_motion.hpp"

namespace ccdlab {

/// A kinematic body: its vertices follow `motion` from their rest positions. A sphere or capsule also gives
/// its exact shape, so `obstacle_contact` can push cloth out of it; a mesh obstacle is met by CCD only.
struct SimObstacle {
  enum class Shape { sphere, capsule, mesh };
  std::string name;
  int body = -1;
  Shape shape = Shape::mesh;
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();  ///< sphere: centre a; capsule: axis segment a–b (rest positions)
  double radius = 0;
  RigidMotion motion;

  /// The point of the segment a–b nearest p (a sphere is the segment a–a): a capsule's or sphere's surface is
  /// the set of points at `radius` from it.
  [[nodiscard]] static Vec3 nearest_on_axis(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    return a + std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0) * ab;
  }
  /// Whether p is inside the exact shape at time t (a mesh obstacle has none: never).
  [[nodiscard]] bool contains(const Vec3& p, double t) const {
    if (shape == Shape::mesh) return false;
    const Eigen::Isometry3d pose = motion.at(t);
    const Vec3 pa = pose * a, pb = shape == Shape::capsule ? Vec3(pose * b) : pa;
    return (p - nearest_on_axis(p, pa, pb)).squaredNorm() < radius * radius;
  }
};

/// What every effect may read: the topology, the bodies, the rest shape and who moves freely.
struct SimSetup {
  const TriMesh* mesh = nullptr;
  std::vector<Body> bodies;
  Positions rest;                 ///< positions at time 0 (rest lengths and angles come from here)
  std::vector<double> inv_mass;   ///< per vertex; 0 = not moved by physics (pinned, obstacle, handle)
  double thickness = 0;           ///< cloth thickness (contact distance), scene units
  int threads = 1;
  std::uint64_t seed = 1;         ///< for effects with randomness (wind turbulence): same seed, same frames
  std::vector<SimObstacle> obstacles;
  /// Per vertex: the obstacle whose rigid motion moves it (its own vertices, and cloth pinned to it), or −1.
  std::vector<int> follows;
  /// Per vertex: 1 when it belongs to a cloth body.
  [[nodiscard]] std::vector<char> cloth_mask() const {
    std::vector<char> mask(rest.size(), 0);
    for (const Body& b : bodies)
      if (b.kind == BodyKind::cloth) std::fill(mask.begin() + b.vertex_begin, mask.begin() + b.vertex_end, 1);
    return mask;
  }
  /// Vertices of the cloth bodies (what physics moves), in index order.
  [[nodiscard]] std::vector<Index> cloth_vertices() const {
    std::vector<Index> out;
    for (const Body& b : bodies)
      if (b.kind == BodyKind::cloth)
        for (Index v = b.vertex_begin; v < b.vertex_end; ++v) out.push_back(v);
    return out;
  }
};

/// The simulated state during a sub-step from time t to t + dt.
struct SimState {
  Positions x;  ///< positions at t
  Positions p;  ///< predicted positions at t + dt (what constraints and collisions move)
  Positions v;  ///< velocities
  double time = 0;  ///< t
  int iteration = 0;  ///< constraint iteration within the sub-step (XPBD resets its multipliers at 0)
};

/// What an effect did, for the per-effect report (simulate's metadata): how often it ran, how long, and one
/// effect-specific count (constraints projected, contacts resolved, vertices pushed out …).
struct EffectCounters {
  std::uint64_t calls = 0;
  std::uint64_t work = 0;   ///< effect-specific (see each effect's `work_name`)
  double ms = 0;
};

class Effect {
 public:
  enum class Stage { force, constraint, collision };
  virtual ~Effect() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  [[nodiscard]] virtual Stage stage() const = 0;
  /// What `EffectCounters::work` counts, for reports ("constraints", "contacts resolved" …).
  [[nodiscard]] virtual std::string_view work_name() const = 0;
  /// Once, before the first sub-step: rest lengths, pinned sets, … An effect may fix vertices here (inv_mass 0).
  virtual void setup(SimSetup& /*setup*/) {}
  /// One application: a force effect changes s.v, a constraint effect s.p, a collision effect s.p and s.v.
  /// Returns the effect-specific work done (added to the counters by the simulator).
  virtual std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) = 0;
  /// Effect-specific totals for the report (ccd_contact: passes run, self passes, contacts left), or empty.
  [[nodiscard]] virtual nlohmann::json stats() const { return nlohmann::json::object(); }
};

}  // namespace ccdlab
