#pragma once
// The keys (kind, feature a, feature b) of a contact list, in its order: what two lists are compared by when
// their times and coordinates may differ in the last bits.
#include <tuple>
#include <vector>

#include "framework/primitive/contact.hpp"

namespace ccdlab::test {

using ContactKey = std::tuple<ContactKind, Index, Index>;

inline std::vector<ContactKey> keys(const Contacts& cs) {
  std::vector<ContactKey> k;
  for (const Contact& c : cs) k.push_back(c.key());
  return k;
}

}  // namespace ccdlab::test
