#include "framework/primitive/contact.hpp"

#include "framework/geometry/distance.hpp"

#include <algorithm>

namespace ccdlab {

void sort_contacts(Contacts& contacts) {
  std::sort(contacts.begin(), contacts.end(), [](const Contact& x, const Contact& y) { return x.key() < y.key(); });
}

std::uint64_t contact_set_hash(std::span<const Contact> sorted_contacts, std::uint64_t seed) {
  std::uint64_t h = seed;
  auto mix = [&h](std::uint64_t value) {
    for (int i = 0; i < 8; ++i) {
      h ^= (value >> (8 * i)) & 0xffu;
      h *= 1099511628211ull;
    }
  };
  for (const Contact& c : sorted_contacts) {
    mix(std::uint64_t(c.kind));
    mix(std::uint64_t(std::uint32_t(c.feature_a)));
    mix(std::uint64_t(std::uint32_t(c.feature_b)));
  }
  return h;
}

std::array<double, 2> contact_coords(const VertexFaceQuery& q, double t) {
  auto at = [t](const Vec3& a, const Vec3& b) -> Vec3 { return a + t * (b - a); };
  const auto c = closest_point_triangle(at(q.v_t0, q.v_t1), at(q.f0_t0, q.f0_t1), at(q.f1_t0, q.f1_t1), at(q.f2_t0, q.f2_t1));
  return {c.bary[1], c.bary[2]};
}

std::array<double, 2> contact_coords(const EdgeEdgeQuery& q, double t) {
  auto at = [t](const Vec3& a, const Vec3& b) -> Vec3 { return a + t * (b - a); };
  const auto c = closest_segment_segment(at(q.ea0_t0, q.ea0_t1), at(q.ea1_t0, q.ea1_t1), at(q.eb0_t0, q.eb0_t1), at(q.eb1_t0, q.eb1_t1));
  return {c.s, c.t};
}

std::string_view to_string(ContactKind kind) { return kind == ContactKind::vf ? "vf" : "ee"; }

Vec3 contact_normal(const Contact& c, const Positions& x_t0, const Positions& x_t1) {
  const auto p = [&](int i) {
    const Index v = c.vertices[std::size_t(i)];
    return Vec3((1 - c.toi) * x_t0[v] + c.toi * x_t1[v]);
  };
  const Vec3 n = c.kind == ContactKind::vf ? Vec3((p(2) - p(1)).cross(p(3) - p(1))) : Vec3((p(1) - p(0)).cross(p(3) - p(2)));
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

}  // namespace ccdlab
