// wind: aerodynamic drag towards a wind velocity, per triangle, with turbulence. Each cloth triangle feels
// F = drag · area · ((w − v)·n) n — only the normal component of the relative air velocity pushes a sheet —
// split equally over its three vertices (unit mass per vertex). w is the mean wind plus a smooth gust field: a
// sum of four travelling sine waves in space and time whose directions and phases come from the scene's seed,
// so the same seed gives the same gusts, bit for bit.
#include <array>
#include <cmath>

#include "strategies/effects/effects.hpp"

namespace ccdlab {
namespace {

std::uint64_t splitmix64(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
double unit(std::uint64_t& s) { return double(splitmix64(s) >> 11) * 0x1.0p-53; }

class Wind final : public Effect {
 public:
  using Params = WindParams;
  explicit Wind(Params p) : p_(p) {}
  [[nodiscard]] std::string_view name() const override { return "wind"; }
  [[nodiscard]] Stage stage() const override { return Stage::force; }
  [[nodiscard]] std::string_view work_name() const override { return "triangles"; }

  void setup(SimSetup& setup) override {
    std::uint64_t s = setup.seed * 0x2545f4914f6cdd1dull + 17;
    for (auto& w : waves_) {
      const double theta = 2 * M_PI * unit(s), z = 2 * unit(s) - 1;
      w.k = 2.0 * Vec3(std::sqrt(1 - z * z) * std::cos(theta), z, std::sqrt(1 - z * z) * std::sin(theta));
      w.omega = 1 + 3 * unit(s);
      w.phase = 2 * M_PI * unit(s);
      const double a = 2 * M_PI * unit(s), b = 2 * unit(s) - 1;
      w.dir = Vec3(std::sqrt(1 - b * b) * std::cos(a), b, std::sqrt(1 - b * b) * std::sin(a));
    }
  }

  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override {
    const TriMesh& mesh = *setup.mesh;
    const double gust = p_.turbulence * p_.velocity.norm() / 2;
    std::uint64_t n = 0;
    for (const Body& body : setup.bodies) {
      if (body.kind != BodyKind::cloth) continue;
      for (Index f = body.face_begin; f < body.face_end; ++f) {
        const auto& t = mesh.face(f);
        const Vec3 &a = s.x[std::size_t(t[0])], &b = s.x[std::size_t(t[1])], &c = s.x[std::size_t(t[2])];
        const Vec3 cross = (b - a).cross(c - a);
        const double twice_area = cross.norm();
        if (twice_area == 0) continue;
        const Vec3 normal = cross / twice_area, centre = (a + b + c) / 3;
        Vec3 w = p_.velocity;
        for (const Wave& wave : waves_) w += gust * std::sin(wave.k.dot(centre) - wave.omega * s.time + wave.phase) * wave.dir;
        const Vec3 v = (s.v[std::size_t(t[0])] + s.v[std::size_t(t[1])] + s.v[std::size_t(t[2])]) / 3;
        const Vec3 force = p_.drag * 0.5 * twice_area * (w - v).dot(normal) * normal;
        for (Index i : t)
          if (setup.inv_mass[std::size_t(i)] > 0) s.v[std::size_t(i)] += dt * setup.inv_mass[std::size_t(i)] * force / 3;
        ++n;
      }
    }
    return n;
  }

 private:
  struct Wave {
    Vec3 k, dir;
    double omega = 1, phase = 0;
  };
  Params p_;
  std::array<Wave, 4> waves_{};
};

}  // namespace

std::unique_ptr<Effect> make_wind(const ParamValues& p) {
  return std::make_unique<Wind>(Wind::Params{Vec3(p.real("vx"), p.real("vy"), p.real("vz")), p.real("drag"), p.real("turbulence")});
}

}  // namespace ccdlab
