#include "framework/primitive/contact.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>

#include "framework/geometry/distance.hpp"

namespace ccdlab {

void sort_contacts_into(std::span<const std::span<const Contact>> parts, Contacts& out, ContactSortScratch& scratch) {
  std::size_t n = 0;
  for (const auto& part : parts) n += part.size();
  const auto packable_one = [](const Contact& c) { return c.feature_a >= 0 && c.feature_b >= 0 && std::uint8_t(c.kind) <= 1; };
  bool packable = n <= std::numeric_limits<std::uint32_t>::max();
  for (const auto& part : parts) packable = packable && std::all_of(part.begin(), part.end(), packable_one);
  if (n < 256 || !packable) {
    out.clear();
    for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
    std::sort(out.begin(), out.end(), [](const Contact& x, const Contact& y) { return x.key() < y.key(); });
    return;
  }
  // The sort is serial, at the end of every step, and a contact is 56 bytes: rather than std::sort moving them
  // around, the packed keys and where each contact is are radix-sorted (LSD, 11-bit digits — a 2048-entry
  // histogram stays in L1 —, a digit equal in every key skipped) and each contact copied once, from the threads'
  // lists to its place. The packing keeps key()'s order: kind, then feature_a, then feature_b, each in as many
  // bits as its largest value needs.
  using Keyed = ContactSortScratch::Keyed;
  std::vector<Keyed>& a = scratch.keys;
  std::vector<Keyed>& b = scratch.swap;
  a.resize(n), b.resize(n);
  std::uint32_t max_a = 0, max_b = 0;
  for (const auto& part : parts)
    for (const Contact& c : part) max_a = std::max(max_a, std::uint32_t(c.feature_a)), max_b = std::max(max_b, std::uint32_t(c.feature_b));
  const int bits_b = std::bit_width(max_b), bits_ab = std::bit_width(max_a) + bits_b;  // ≤ 62: ids < 2³¹
  std::uint64_t any = 0, every = ~0ull;
  std::size_t i = 0;
  for (const auto& part : parts)
    for (const Contact& c : part) {
      const std::uint64_t key = std::uint64_t(c.kind) << bits_ab | std::uint64_t(std::uint32_t(c.feature_a)) << bits_b |
                                std::uint64_t(std::uint32_t(c.feature_b));
      a[i++] = {key, &c};
      any |= key, every &= key;
    }
  constexpr int kDigit = 11;
  constexpr std::uint64_t kMask = (1u << kDigit) - 1;
  std::vector<std::size_t>& start = scratch.histogram;
  for (int shift = 0; shift <= bits_ab; shift += kDigit) {
    if (((any ^ every) >> shift & kMask) == 0) continue;
    start.assign(kMask + 2, 0);
    for (const Keyed& k : a) ++start[(k.key >> shift & kMask) + 1];
    for (std::size_t d = 0; d <= kMask; ++d) start[d + 1] += start[d];
    for (const Keyed& k : a) b[start[k.key >> shift & kMask]++] = k;
    a.swap(b);
  }
  out.resize(n);
  for (std::size_t j = 0; j < n; ++j) out[j] = *a[j].contact;
}

void sort_contacts(Contacts& contacts, ContactSortScratch& scratch) {
  scratch.moved.assign(contacts.begin(), contacts.end());
  const std::span<const Contact> all(scratch.moved);
  sort_contacts_into({&all, 1}, contacts, scratch);
}

void sort_contacts(Contacts& contacts) {
  ContactSortScratch scratch;
  sort_contacts(contacts, scratch);
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
