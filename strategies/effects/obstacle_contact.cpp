// obstacle_contact: pushes cloth vertices out of the scene's sphere and capsule obstacles (exact shapes, at
// their scripted pose at t + dt) to the cloth thickness, with Coulomb friction in position form (Müller et al.
// 2007, Macklin et al. 2014): the vertex's motion relative to the obstacle's surface, tangent to it, is removed
// up to friction × the penetration depth — a spinning ball drags the cloth with it. Mesh obstacles are met by
// `ccd_contact` only.
#include "strategies/effects/effects.hpp"

namespace ccdlab {
namespace {

class ObstacleContact final : public Effect {
 public:
  explicit ObstacleContact(double friction) : friction_(friction) {}
  [[nodiscard]] std::string_view name() const override { return "obstacle_contact"; }
  [[nodiscard]] Stage stage() const override { return Stage::constraint; }
  [[nodiscard]] std::string_view work_name() const override { return "vertices pushed out"; }
  void setup(SimSetup& setup) override { cloth_ = setup.cloth_vertices(); }

  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override {
    std::uint64_t n = 0;
    for (const SimObstacle& ob : setup.obstacles) {
      if (ob.shape == SimObstacle::Shape::mesh) continue;
      const Eigen::Isometry3d now = ob.motion.at(s.time + dt), before = ob.motion.at(s.time);
      const Eigen::Isometry3d back = before * now.inverse();  // where a surface point at t + dt was at t
      const Vec3 a = now * ob.a, b = now * ob.b;
      const double reach = ob.radius + setup.thickness;
      for (Index v : cloth_) {
        const auto i = std::size_t(v);
        if (setup.inv_mass[i] == 0) continue;
        Vec3& p = s.p[i];
        const Vec3 d = p - SimObstacle::nearest_on_axis(p, a, ob.shape == SimObstacle::Shape::capsule ? b : a);
        const double dist = d.norm();
        if (dist >= reach || dist < 1e-12) continue;
        const Vec3 normal = d / dist;
        const double depth = reach - dist;
        p += depth * normal;
        // Friction: the motion of the vertex relative to the surface point under it, in the tangent plane.
        const Vec3 surface_motion = p - back * p;
        Vec3 slip = (p - s.x[i]) - surface_motion;
        slip -= slip.dot(normal) * normal;
        const double slip_len = slip.norm(), limit = friction_ * depth;
        p -= slip_len <= limit ? slip : Vec3(slip * (limit / slip_len));
        ++n;
      }
    }
    return n;
  }

 private:
  double friction_;
  std::vector<Index> cloth_;
};

}  // namespace

std::unique_ptr<Effect> make_obstacle_contact(const ParamValues& p) {
  return std::make_unique<ObstacleContact>(p.real("friction"));
}

}  // namespace ccdlab
