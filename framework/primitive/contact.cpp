#include "framework/primitive/contact.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>

#include "framework/geometry/distance.hpp"

namespace ccdlab {

namespace {

using Keyed = ContactSortScratch::Keyed;
constexpr int kIdBits = 31;  // the merge's layout: kind << 62 | feature_a << 31 | feature_b

bool packable(const Contact& c) { return c.feature_a >= 0 && c.feature_b >= 0 && std::uint8_t(c.kind) <= 1; }

/// One part's keys, sorted. The sort is serial per part, at the end of every step, and a contact is 56 bytes:
/// rather than std::sort moving them around, the packed keys and where each contact is are radix-sorted (LSD,
/// 11-bit digits — a 2048-entry histogram stays in L1 —, a digit equal in every key skipped). The packing keeps
/// key()'s order: kind, then feature_a, then feature_b, each in as many bits as the part's largest value needs;
/// then each key is rewritten to the layout all parts share, which the merge compares.
void sort_part(std::span<const Contact> contacts, ContactSortScratch::Part& part) {
  part.packed = std::all_of(contacts.begin(), contacts.end(), packable);
  if (!part.packed) return;
  std::vector<Keyed>& a = part.keys;
  std::vector<Keyed>& b = part.swap;
  a.resize(contacts.size()), b.resize(contacts.size());
  std::uint32_t max_a = 0, max_b = 0;
  for (const Contact& c : contacts) max_a = std::max(max_a, std::uint32_t(c.feature_a)), max_b = std::max(max_b, std::uint32_t(c.feature_b));
  const int bits_b = std::bit_width(max_b), bits_ab = std::bit_width(max_a) + bits_b;  // ≤ 62: ids < 2³¹
  std::uint64_t any = 0, every = ~0ull;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    const std::uint64_t key = std::uint64_t(c.kind) << bits_ab | std::uint64_t(std::uint32_t(c.feature_a)) << bits_b |
                              std::uint64_t(std::uint32_t(c.feature_b));
    a[i] = {key, &c};
    any |= key, every &= key;
  }
  constexpr int kDigit = 11;
  constexpr std::uint64_t kMask = (1u << kDigit) - 1;
  std::vector<std::size_t>& start = part.histogram;
  for (int shift = 0; shift <= bits_ab; shift += kDigit) {
    if (((any ^ every) >> shift & kMask) == 0) continue;
    start.assign(kMask + 2, 0);
    for (const Keyed& k : a) ++start[(k.key >> shift & kMask) + 1];
    for (std::size_t d = 0; d <= kMask; ++d) start[d + 1] += start[d];
    for (const Keyed& k : a) b[start[k.key >> shift & kMask]++] = k;
    a.swap(b);
  }
  const std::uint64_t mask_b = (std::uint64_t(1) << bits_b) - 1, mask_a = (std::uint64_t(1) << (bits_ab - bits_b)) - 1;
  for (Keyed& k : a)
    k.key = (k.key >> bits_ab) << 2 * kIdBits | (k.key >> bits_b & mask_a) << kIdBits | (k.key & mask_b);
}

/// The sorted parts merged into `out`, each contact copied once (one part: in order; two: the two-way merge;
/// more: the least head of a heap).
void merge_parts(std::span<const ContactSortScratch::Part> parts, std::size_t n, Contacts& out) {
  out.resize(n);
  Contact* to = out.data();
  std::vector<std::span<const Keyed>> runs;
  for (const auto& part : parts)
    if (!part.keys.empty()) runs.emplace_back(part.keys);
  if (runs.size() == 2) {
    const Keyed *x = runs[0].data(), *x_end = x + runs[0].size(), *y = runs[1].data(), *y_end = y + runs[1].size();
    while (x != x_end && y != y_end) *to++ = *(x->key < y->key ? x++ : y++)->contact;
    for (; x != x_end; ++x) *to++ = *x->contact;
    for (; y != y_end; ++y) *to++ = *y->contact;
    return;
  }
  if (runs.size() <= 1) {
    if (runs.size() == 1)
      for (const Keyed& k : runs[0]) *to++ = *k.contact;
    return;
  }
  using Head = std::pair<std::uint64_t, std::size_t>;  // key, run
  std::vector<Head> heap;
  std::vector<std::size_t> next(runs.size(), 0);
  for (std::size_t r = 0; r < runs.size(); ++r) heap.emplace_back(runs[r][0].key, r);
  const auto later = [](const Head& p, const Head& q) { return p > q; };
  std::make_heap(heap.begin(), heap.end(), later);
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const std::size_t r = heap.back().second;
    *to++ = *runs[r][next[r]++].contact;
    if (next[r] < runs[r].size()) {
      heap.back().first = runs[r][next[r]].key;
      std::push_heap(heap.begin(), heap.end(), later);
    } else {
      heap.pop_back();
    }
  }
}

}  // namespace

void sort_contacts_into(std::span<const std::span<const Contact>> parts, Contacts& out, ContactSortScratch& scratch,
                        const PartRunner& run_parts) {
  std::size_t n = 0;
  for (const auto& part : parts) n += part.size();
  scratch.parts.resize(std::max(scratch.parts.size(), parts.size()));
  const std::span<ContactSortScratch::Part> sorted(scratch.parts.data(), parts.size());
  const auto task = [&](std::size_t i) { sort_part(parts[i], sorted[i]); };
  bool packed = n >= 256;
  if (packed) {
    if (run_parts) run_parts(parts.size(), task);
    else for (std::size_t i = 0; i < parts.size(); ++i) task(i);
    packed = std::all_of(sorted.begin(), sorted.end(), [](const auto& p) { return p.packed; });
  }
  if (!packed) {  // few, or a key that does not pack: the comparison sort
    out.clear();
    for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
    std::sort(out.begin(), out.end(), [](const Contact& x, const Contact& y) { return x.key() < y.key(); });
    return;
  }
  merge_parts(sorted, n, out);
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
