#pragma once
// What the broad phase hands to the narrow phase: candidate face pairs whose swept bounding volumes overlap.
#include <compare>
#include <cstdint>
#include <vector>

#include "framework/mesh/tri_mesh.hpp"

namespace ccdlab {

struct FacePair {
  Index a;
  Index b;
  auto operator<=>(const FacePair&) const = default;
};

struct TraversalOutput {
  std::vector<FacePair> pairs;
  std::uint64_t bv_tests = 0;  ///< BV overlap tests performed

  void clear() {
    pairs.clear();
    bv_tests = 0;
  }
};

}  // namespace ccdlab
