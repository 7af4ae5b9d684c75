#include "framework/traversal/candidates.hpp"

#include <algorithm>

namespace ccdlab {

void TraversalStats::add(const TraversalStats& o) {
  bv_tests += o.bv_tests;
  tasks += o.tasks;
  serial_ms += o.serial_ms;
  front_nodes += o.front_nodes;
  front_bytes += o.front_bytes;
  front_visited += o.front_visited;
  sprouted += o.sprouted;
  pruned += o.pruned;
  rebuilds += o.rebuilds;
  cone_culled += o.cone_culled;
  contour_edges += o.contour_edges;
}

void CandidateList::use_parts(int n) {
  if (n > num_parts()) parts_.resize(std::size_t(n));
}

void CandidateList::reserve(int n, std::size_t pairs) {
  use_parts(n);
  for (int i = 0; i < n; ++i) {
    FacePairs& p = part(i);
    p.reserve(p.size() + std::min(pairs, kMaxReservedPairs));
  }
}

std::size_t CandidateList::size() const {
  std::size_t n = 0;
  for (const auto& p : parts_) n += p.value.size();
  return n;
}

void CandidateList::clear() {
  for (auto& p : parts_) p.value.clear();
}

void CandidateList::release() {
  for (auto& p : parts_) FacePairs().swap(p.value);
}

FacePairs CandidateList::flatten() const {
  FacePairs all;
  all.reserve(size());
  for (const auto& p : parts_) all.insert(all.end(), p.value.begin(), p.value.end());
  return all;
}

}  // namespace ccdlab
