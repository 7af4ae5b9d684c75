// sort_contacts: the radix sort of packed keys orders contacts exactly as comparing Contact::key() does, keeps
// each contact whole, and falls back to the comparison sort where a key does not pack; sort_contacts_into gives
// the same list from the contacts split into parts (the threads' lists), however they are split and in whatever
// order the parts are sorted.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <set>
#include <span>
#include <vector>
#include <tuple>

#include "framework/primitive/contact.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// `n` contacts with distinct keys, drawn from ids spread over [0, 2³¹) (and the extremes), in random order;
/// each carries its id pair in its other fields so that a torn move shows.
Contacts random_contacts(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<Index> any_id(0, std::numeric_limits<Index>::max());
  std::uniform_int_distribution<Index> small_id(0, 40);  // many equal feature_a, so feature_b decides
  std::set<std::tuple<ContactKind, Index, Index>> seen;
  Contacts out;
  while (out.size() < n) {
    Contact c{};
    c.kind = rng() % 2 ? ContactKind::vf : ContactKind::ee;
    c.feature_a = rng() % 3 ? small_id(rng) : any_id(rng);
    c.feature_b = rng() % 7 == 0 ? std::numeric_limits<Index>::max() - Index(rng() % 3) : any_id(rng);
    if (!seen.insert(c.key()).second) continue;
    c.vertices = {c.feature_a, c.feature_b, Index(out.size()), 0};
    c.toi = double(c.feature_a) * 0.5;
    c.coords = {double(c.feature_b), -1.0};
    out.push_back(c);
  }
  return out;
}

void expect_sorted_like_keys(Contacts contacts, ContactSortScratch& scratch) {
  Contacts reference = contacts;
  std::sort(reference.begin(), reference.end(), [](const Contact& x, const Contact& y) { return x.key() < y.key(); });
  sort_contacts(contacts, scratch);
  ASSERT_EQ(contacts.size(), reference.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact &c = contacts[i], &r = reference[i];
    ASSERT_EQ(c.key(), r.key()) << "at " << i;
    EXPECT_EQ(c.vertices, r.vertices);
    EXPECT_EQ(c.toi, r.toi);
    EXPECT_EQ(c.coords, r.coords);
  }
}

TEST(ContactSort, RadixOrderEqualsKeyOrderAtEverySize) {
  ContactSortScratch scratch;  // reused across sizes, as the pipeline reuses it across steps
  for (const std::size_t n : {0, 1, 255, 256, 257, 5000, 40000, 1000})
    expect_sorted_like_keys(random_contacts(n, std::uint32_t(n) + 7), scratch);
}

TEST(ContactSort, MeshSizedIdsPackIntoFewerDigits) {
  // Ids of a mesh (below 2¹⁷ here): the key packs into 35 bits, sorted in four 11-bit digits.
  std::mt19937 rng(11);
  Contacts contacts;
  std::set<std::tuple<ContactKind, Index, Index>> seen;
  while (contacts.size() < 30000) {
    Contact c{};
    c.kind = rng() % 2 ? ContactKind::vf : ContactKind::ee;
    c.feature_a = Index(rng() % 100000), c.feature_b = Index(rng() % 130000);
    if (!seen.insert(c.key()).second) continue;
    c.vertices = {c.feature_a, c.feature_b, Index(contacts.size()), 0};
    contacts.push_back(c);
  }
  ContactSortScratch scratch;
  expect_sorted_like_keys(contacts, scratch);
  for (Contact& c : contacts) c.kind = ContactKind::ee, c.feature_a = 7;  // equal digits skipped; feature_b decides
  Contacts unique;
  std::set<Index> b_seen;
  for (const Contact& c : contacts)
    if (b_seen.insert(c.feature_b).second) unique.push_back(c);
  expect_sorted_like_keys(unique, scratch);
}

TEST(ContactSort, PartsSortIntoTheOrderOfTheWholeWhateverTheSplit) {
  ContactSortScratch scratch;
  for (const std::size_t n : {0, 100, 300, 20000}) {
    const Contacts all = random_contacts(n, std::uint32_t(n) + 3);
    Contacts whole = all;
    sort_contacts(whole, scratch);
    std::mt19937 rng{std::uint32_t(n)};
    for (const std::size_t count : {1, 2, 3, 7}) {  // parts of random sizes, some empty
      std::vector<std::size_t> cuts{0, n};
      for (std::size_t k = 1; k < count; ++k) cuts.push_back(n == 0 ? 0 : rng() % (n + 1));
      std::sort(cuts.begin(), cuts.end());
      std::vector<std::span<const Contact>> parts;
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) parts.emplace_back(all.data() + cuts[k], cuts[k + 1] - cuts[k]);
      // The parts' sorts in turn, and in reverse order as threads may finish them: one order either way.
      const PartRunner backwards = [](std::size_t k, const std::function<void(std::size_t)>& task) {
        while (k > 0) task(--k);
      };
      for (const PartRunner& runner : {PartRunner{}, backwards}) {
        Contacts out = random_contacts(5, 1);  // replaced, not appended to
        sort_contacts_into(parts, out, scratch, runner);
        ASSERT_EQ(out.size(), whole.size()) << n << " in " << count;
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_EQ(out[i].key(), whole[i].key()) << n << " in " << count << " at " << i;
          EXPECT_EQ(out[i].vertices, whole[i].vertices);
          EXPECT_EQ(out[i].toi, whole[i].toi);
        }
      }
    }
  }
}

TEST(ContactSort, KeysThatDoNotPackFallBackToTheComparisonSort) {
  Contacts contacts = random_contacts(600, 3);
  contacts[17].feature_b = -5;  // not a feature id: no 31-bit packing
  ContactSortScratch scratch;
  expect_sorted_like_keys(contacts, scratch);
}

}  // namespace
}  // namespace ccdlab
