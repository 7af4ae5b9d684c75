#include "framework/queries/hard_cases.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include <fmt/format.h>

namespace ccdlab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using Points = std::array<Vec3, 8>;  // query order: 4 points at t0, then the same 4 at t1

/// A perturbation: a name and a signed offset (dyadic steps, or one ulp of the coordinate it moves).
struct Perturbation {
  std::string name;
  double step;  // > 0; the offset is ±step, or ±1 ulp when step == 0
};
const std::vector<Perturbation>& perturbations() {
  static const std::vector<Perturbation> p = {
      {"2^-10", 0x1p-10}, {"2^-20", 0x1p-20}, {"2^-30", 0x1p-30}, {"2^-40", 0x1p-40}, {"1ulp", 0.0}};
  return p;
}
/// x moved by +1 (sign > 0) or −1 perturbation.
double moved(double x, const Perturbation& p, int sign) {
  if (p.step == 0) return std::nextafter(x, sign > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
  return x + sign * p.step;
}

Vec3 v3(double x, double y, double z) { return Vec3(x, y, z); }

class Generator {
 public:
  void add(const std::string& family, ContactKind kind, const std::string& label, const Points& p, bool truth, double toi) {
    QuerySet& s = set(family, kind);
    if (kind == ContactKind::vf) s.vf.push_back({p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]});
    else s.ee.push_back({p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]});
    s.truth.push_back(truth ? 1 : 0);
    s.toi.push_back(truth ? toi : kNaN);
    s.origin.push_back(fmt::format("hard-cases/{}: {}", family, label));
    base_.push_back({kind, label + " [" + family + "]", p, truth, toi});
  }

  /// The transformed copies of every case added so far (exact transforms only).
  void add_transformed() {
    const auto cases = base_;
    for (const auto& c : cases) {
      add_scaled("tiny-motion", c, 0x1p-40, v3(0, 0, 0), "x 2^-40");
      add_scaled("large-coordinates", c, 0x1p20, v3(0, 0, 0), "x 2^20");
      add_scaled("large-coordinates", c, 1.0, v3(0x1p20, -0x1p20, 0x1p19), "+ (2^20, -2^20, 2^19)");
      add_sheared(c);
    }
  }

  std::vector<QuerySet> take() {
    std::vector<QuerySet> out;
    for (auto& [name, s] : sets_) out.push_back(std::move(s));
    return out;
  }

 private:
  struct Case {
    ContactKind kind;
    std::string label;
    Points p;
    bool truth;
    double toi;
  };

  QuerySet& set(const std::string& family, ContactKind kind) {
    auto [it, fresh] = sets_.try_emplace(family);
    if (fresh) {
      it->second.name = "hard-cases/" + family;
      it->second.scene = it->second.collection = "hard-cases";
      it->second.kind = kind;
    }
    return it->second;
  }

  void add_scaled(const std::string& family, const Case& c, double scale, const Vec3& shift, const std::string& how) {
    Points q;
    for (int i = 0; i < 8; ++i) {
      q[i] = c.p[i] * scale + shift;
      const Vec3 back = (q[i] - shift) / scale;
      if (back != c.p[i]) return;  // not exact: the transformed query would be a different question
    }
    add_copy(family, c, q, how);
  }

  void add_copy(const std::string& family, const Case& c, const Points& q, const std::string& how) {
    // Keep the two kinds apart: sets hold one kind of query.
    const std::string fam = family + (c.kind == ContactKind::vf ? "-vf" : "-ee");
    QuerySet& s = set(fam, c.kind);
    if (c.kind == ContactKind::vf) s.vf.push_back({q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7]});
    else s.ee.push_back({q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7]});
    s.truth.push_back(c.truth ? 1 : 0);
    s.toi.push_back(c.truth ? c.toi : kNaN);
    s.origin.push_back(fmt::format("hard-cases/{}: {} {}", fam, c.label, how));
  }

  /// The case under the shear (x, y, z) → (x, y, x + y + z): linear and invertible, so every answer and time of
  /// contact is the same, but the cases' axis-aligned planes and lines tilt, and all three coordinates of a
  /// cross product or a difference are in play (the exact tester's event search sees what it sees in a mesh).
  void add_sheared(const Case& c) {
    Points q;
    for (int i = 0; i < 8; ++i) {
      const Vec3& x = c.p[i];
      const double xy = x[0] + x[1], z = xy + x[2];
      if (!sum_is_exact(x[0], x[1], xy) || !sum_is_exact(xy, x[2], z)) return;  // a different question
      q[i] = v3(x[0], x[1], z);
    }
    add_copy("tilted", c, q, "sheared z += x + y");
  }
  /// a + b == s exactly (the rounding error of the sum, found by TwoSum, is zero).
  static bool sum_is_exact(double a, double b, double s) {
    const double bb = s - a, aa = s - bb;
    return (a - aa) + (b - bb) == 0;
  }

  std::map<std::string, QuerySet> sets_;
  std::vector<Case> base_;
};

// The reference face: f0 = (0, ½, ½), f1 = (1, ½, ½), f2 = (0, 3/2, ½), static, in the plane z = ½.
// Its edge f0f1 lies on y = ½; the inside is x ≥ 0, y ≥ ½, x + y ≤ 3/2.
const Vec3 F0 = v3(0, 0.5, 0.5), F1 = v3(1, 0.5, 0.5), F2 = v3(0, 1.5, 0.5);
Points vf(const Vec3& v0, const Vec3& v1, const Vec3& f0 = F0, const Vec3& f1 = F1, const Vec3& f2 = F2) {
  return {v0, f0, f1, f2, v1, f0, f1, f2};
}
// The reference edge a: (0, ½, ½) – (1, ½, ½), static.
const Vec3 A0 = v3(0, 0.5, 0.5), A1 = v3(1, 0.5, 0.5);
Points ee(const Vec3& b0_t0, const Vec3& b1_t0, const Vec3& b0_t1, const Vec3& b1_t1) {
  return {A0, A1, b0_t0, b1_t0, A0, A1, b0_t1, b1_t1};
}

void vertex_face_families(Generator& g) {
  const ContactKind k = ContactKind::vf;
  // Contact exactly at t = 1: the vertex comes down onto the face and stops on it.
  g.add("contact-at-t1", k, "lands at t=1", vf(v3(0.25, 0.75, 1.5), v3(0.25, 0.75, 0.5)), true, 1.0);
  for (const auto& p : perturbations()) {
    g.add("contact-at-t1", k, "stops " + p.name + " short", vf(v3(0.25, 0.75, 1.5), v3(0.25, 0.75, moved(0.5, p, +1))), false, kNaN);
    g.add("contact-at-t1", k, "goes " + p.name + " through", vf(v3(0.25, 0.75, 1.5), v3(0.25, 0.75, moved(0.5, p, -1))), true, kNaN);
  }
  // Contact exactly at t = 0: the vertex starts on the face and leaves.
  g.add("contact-at-t0", k, "starts on the face", vf(v3(0.25, 0.75, 0.5), v3(0.25, 0.75, 1.5)), true, 0.0);
  for (const auto& p : perturbations()) {
    g.add("contact-at-t0", k, "starts " + p.name + " above", vf(v3(0.25, 0.75, moved(0.5, p, +1)), v3(0.25, 0.75, 1.5)), false, kNaN);
    g.add("contact-at-t0", k, "starts " + p.name + " below", vf(v3(0.25, 0.75, moved(0.5, p, -1)), v3(0.25, 0.75, 1.5)), true, kNaN);
  }
  // Vertex through an edge (y = ½) and through a corner (f1), at t = ½.
  g.add("vertex-on-edge", k, "through the edge", vf(v3(0.5, 0.5, 1.5), v3(0.5, 0.5, -0.5)), true, 0.5);
  g.add("vertex-on-vertex", k, "through the corner f1", vf(v3(1, 0.5, 1.5), v3(1, 0.5, -0.5)), true, 0.5);
  for (const auto& p : perturbations()) {
    const double out = moved(0.5, p, -1), in = moved(0.5, p, +1);
    g.add("vertex-on-edge", k, p.name + " outside", vf(v3(0.5, out, 1.5), v3(0.5, out, -0.5)), false, kNaN);
    g.add("vertex-on-edge", k, p.name + " inside", vf(v3(0.5, in, 1.5), v3(0.5, in, -0.5)), true, 0.5);
    const double beyond = moved(1.0, p, +1);
    g.add("vertex-on-vertex", k, p.name + " beyond the corner", vf(v3(beyond, 0.5, 1.5), v3(beyond, 0.5, -0.5)), false, kNaN);
  }
  // Coplanar motion: the vertex slides in the face's plane and enters through the edge x = 0 at t = 1/3.
  g.add("coplanar-motion", k, "slides in", vf(v3(-1, 0.75, 0.5), v3(2, 0.75, 0.5)), true, 1.0 / 3.0);
  g.add("coplanar-motion", k, "slides along the edge", vf(v3(-1, 0.5, 0.5), v3(2, 0.5, 0.5)), true, 1.0 / 3.0);
  // The face deforms in its plane and its edge f0f2 sweeps over a resting vertex: the two corners' velocities
  // differ in direction, so the time v, f0, f2 become collinear is a root of a quadratic, (7 − √17)/8.
  g.add("coplanar-motion", k, "the face stretches over it",
        {v3(0.25, 0.75, 0.5), F0 + v3(0.5, 0, 0), F1 + v3(0.5, 0, 0), F2 + v3(0.5, 0, 0), v3(0.25, 0.75, 0.5),
         F0 - v3(0.5, 0, 0), F1 + v3(0.5, 0, 0), F2 + v3(0.5, -0.5, 0)},
        true, (7 - std::sqrt(17.0)) / 8);
  for (const auto& p : perturbations()) {
    const double above = moved(0.5, p, +1), beside = moved(0.5, p, -1);
    g.add("coplanar-motion", k, "slides " + p.name + " above the plane", vf(v3(-1, 0.75, above), v3(2, 0.75, above)), false, kNaN);
    g.add("coplanar-motion", k, "slides " + p.name + " beside the edge", vf(v3(-1, beside, 0.5), v3(2, beside, 0.5)), false, kNaN);
  }
  // Zero-area faces: a segment (three collinear corners) and a point (three equal corners).
  const Vec3 mid = v3(0.5, 0.5, 0.5);
  g.add("zero-area-face", k, "through a flat face", vf(v3(0.25, 0.5, 1.5), v3(0.25, 0.5, -0.5), F0, F1, mid), true, 0.5);
  g.add("zero-area-face", k, "through a point face", vf(v3(0.5, 0.5, 1.5), v3(0.5, 0.5, -0.5), mid, mid, mid), true, 0.5);
  for (const auto& p : perturbations()) {
    const double off = moved(0.5, p, +1);
    g.add("zero-area-face", k, p.name + " beside a flat face", vf(v3(0.25, off, 1.5), v3(0.25, off, -0.5), F0, F1, mid), false, kNaN);
    g.add("zero-area-face", k, p.name + " beside a point face", vf(v3(0.5, off, 1.5), v3(0.5, off, -0.5), mid, mid, mid), false, kNaN);
  }
  // No relative motion: static, and everything translating together.
  g.add("no-motion", k, "static, vertex on the face", vf(v3(0.25, 0.75, 0.5), v3(0.25, 0.75, 0.5)), true, 0.0);
  const Vec3 d = v3(0.25, -0.5, 1);
  g.add("no-motion", k, "moving together, vertex on the face",
        {v3(0.25, 0.75, 0.5), F0, F1, F2, v3(0.25, 0.75, 0.5) + d, F0 + d, F1 + d, F2 + d}, true, 0.0);
  for (const auto& p : perturbations()) {
    const double above = moved(0.5, p, +1);
    g.add("no-motion", k, "static, " + p.name + " above", vf(v3(0.25, 0.75, above), v3(0.25, 0.75, above)), false, kNaN);
  }
  // Two roots in one step. Face f0 = 0, f1 = (1,0,0), f2 = (0,1,1) → (0,1,−1) tilts; the vertex moves
  // (px, 0, c) → (px, 2, c); coplanarity: f(t) = 4t² − 2t + c. With c = 3/16 the roots are 1/8 and 3/8: the
  // vertex passes through the face and back (f has the same sign at both ends — root parity sees nothing).
  auto tilt = [](double px, double c) {
    return Points{v3(px, 0, c), v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 1), v3(px, 2, c), v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, -1)};
  };
  g.add("two-roots", k, "through and back (roots 1/8, 3/8)", tilt(0.125, 0.1875), true, 0.125);
  g.add("two-roots", k, "in at 1/8 only", tilt(0.625, 0.1875), true, 0.125);
  g.add("two-roots", k, "tangent (double root 1/4)", tilt(0.25, 0.25), true, 0.25);
  for (const auto& p : perturbations()) {
    g.add("two-roots", k, "tangent, lifted " + p.name, tilt(0.25, moved(0.25, p, +1)), false, kNaN);
    g.add("two-roots", k, "tangent, lowered " + p.name, tilt(0.25, moved(0.25, p, -1)), true, kNaN);
  }
}

void edge_edge_families(Generator& g) {
  const ContactKind k = ContactKind::ee;
  // Edge b along y comes down onto edge a and stops on it at t = 1.
  g.add("edges-contact-at-t1", k, "lands at t=1", ee(v3(0.5, 0, 1.5), v3(0.5, 1, 1.5), v3(0.5, 0, 0.5), v3(0.5, 1, 0.5)), true, 1.0);
  for (const auto& p : perturbations()) {
    const double z = moved(0.5, p, +1), zt = moved(0.5, p, -1);
    g.add("edges-contact-at-t1", k, "stops " + p.name + " short", ee(v3(0.5, 0, 1.5), v3(0.5, 1, 1.5), v3(0.5, 0, z), v3(0.5, 1, z)), false, kNaN);
    g.add("edges-contact-at-t1", k, "goes " + p.name + " through", ee(v3(0.5, 0, 1.5), v3(0.5, 1, 1.5), v3(0.5, 0, zt), v3(0.5, 1, zt)), true, kNaN);
  }
  // Edge b's end point touches edge a (crossing lines, segments meeting at an end).
  g.add("edge-end-on-edge", k, "end touches at t=1/2", ee(v3(0.5, 0.5, 1.5), v3(0.5, 1.5, 1.5), v3(0.5, 0.5, -0.5), v3(0.5, 1.5, -0.5)), true, 0.5);
  g.add("edge-end-on-edge", k, "end touches a's end", ee(v3(1, 0.5, 1.5), v3(1, 1.5, 1.5), v3(1, 0.5, -0.5), v3(1, 1.5, -0.5)), true, 0.5);
  for (const auto& p : perturbations()) {
    const double y = moved(0.5, p, +1), yin = moved(0.5, p, -1), x = moved(1.0, p, +1);
    g.add("edge-end-on-edge", k, "end " + p.name + " short", ee(v3(0.5, y, 1.5), v3(0.5, 1.5, 1.5), v3(0.5, y, -0.5), v3(0.5, 1.5, -0.5)), false, kNaN);
    g.add("edge-end-on-edge", k, "end " + p.name + " across", ee(v3(0.5, yin, 1.5), v3(0.5, 1.5, 1.5), v3(0.5, yin, -0.5), v3(0.5, 1.5, -0.5)), true, 0.5);
    g.add("edge-end-on-edge", k, p.name + " past a's end", ee(v3(x, 0.5, 1.5), v3(x, 1.5, 1.5), v3(x, 0.5, -0.5), v3(x, 1.5, -0.5)), false, kNaN);
  }
  // Parallel edges: b parallel to a comes down; at t = ½ they are collinear and overlap (or are offset).
  g.add("parallel-edges", k, "collinear overlap at t=1/2", ee(v3(0.25, 0.5, 1.5), v3(1.25, 0.5, 1.5), v3(0.25, 0.5, -0.5), v3(1.25, 0.5, -0.5)), true, 0.5);
  for (const auto& p : perturbations()) {
    const double y = moved(0.5, p, +1);
    g.add("parallel-edges", k, "offset " + p.name, ee(v3(0.25, y, 1.5), v3(1.25, y, 1.5), v3(0.25, y, -0.5), v3(1.25, y, -0.5)), false, kNaN);
  }
  // Collinear edges: static end-to-end, and b sliding along a's line into it at t = ½.
  g.add("collinear-edges", k, "static, ends touch", ee(v3(1, 0.5, 0.5), v3(2, 0.5, 0.5), v3(1, 0.5, 0.5), v3(2, 0.5, 0.5)), true, 0.0);
  g.add("collinear-edges", k, "sliding in", ee(v3(1.5, 0.5, 0.5), v3(2.5, 0.5, 0.5), v3(0.5, 0.5, 0.5), v3(1.5, 0.5, 0.5)), true, 0.5);
  for (const auto& p : perturbations()) {
    const double x = moved(1.0, p, +1);
    g.add("collinear-edges", k, "static, gap " + p.name, ee(v3(x, 0.5, 0.5), v3(2, 0.5, 0.5), v3(x, 0.5, 0.5), v3(2, 0.5, 0.5)), false, kNaN);
    g.add("collinear-edges", k, "sliding, stops " + p.name + " short",
          ee(v3(2, 0.5, 0.5), v3(3, 0.5, 0.5), v3(x, 0.5, 0.5), v3(x + 1, 0.5, 0.5)), false, kNaN);
  }
  // Zero-length edges: b is a point passing through a (and a point through a point).
  g.add("zero-length-edge", k, "point through the edge", ee(v3(0.5, 0.5, 1.5), v3(0.5, 0.5, 1.5), v3(0.5, 0.5, -0.5), v3(0.5, 0.5, -0.5)), true, 0.5);
  {
    const Vec3 c = v3(0.5, 0.5, 0.5);
    g.add("zero-length-edge", k, "point through a point",
          {c, c, v3(0.5, 0.5, 1.5), v3(0.5, 0.5, 1.5), c, c, v3(0.5, 0.5, -0.5), v3(0.5, 0.5, -0.5)}, true, 0.5);
  }
  for (const auto& p : perturbations()) {
    const double y = moved(0.5, p, +1);
    g.add("zero-length-edge", k, "point " + p.name + " beside", ee(v3(0.5, y, 1.5), v3(0.5, y, 1.5), v3(0.5, y, -0.5), v3(0.5, y, -0.5)), false, kNaN);
  }
  // No motion: crossing edges touching, or apart by ε.
  g.add("edges-no-motion", k, "static, touching", ee(v3(0.5, 0, 0.5), v3(0.5, 1, 0.5), v3(0.5, 0, 0.5), v3(0.5, 1, 0.5)), true, 0.0);
  for (const auto& p : perturbations()) {
    const double z = moved(0.5, p, +1);
    g.add("edges-no-motion", k, "static, " + p.name + " apart", ee(v3(0.5, 0, z), v3(0.5, 1, z), v3(0.5, 0, z), v3(0.5, 1, z)), false, kNaN);
  }
}

}  // namespace

std::vector<QuerySet> hard_case_sets() {
  Generator g;
  vertex_face_families(g);
  edge_edge_families(g);
  g.add_transformed();
  return g.take();
}

}  // namespace ccdlab
