#include "framework/primitive/contact.hpp"

#include <algorithm>

namespace ccdlab {

void sort_contacts(std::vector<Contact>& contacts) {
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

std::string_view to_string(ContactKind kind) { return kind == ContactKind::vf ? "vf" : "ee"; }

}  // namespace ccdlab
