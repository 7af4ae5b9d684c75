#pragma once
// What the tests iterate: the registries' names and the K type list, never a list written by hand, so that a new
// scheduler, builder, tester or K is covered by every test that loops over them.
#include <string>
#include <vector>

#include "framework/geometry/kdop.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::test {

/// Every K with an axis table (KdopKs).
inline std::vector<int> kdop_ks() { return {KdopKs::values.begin(), KdopKs::values.end()}; }

/// Every registered builder.
inline std::vector<std::string> builders() { return builder_registry().names(); }

/// Every registered scheduler that walks our own BVTT: all but `embree`, a baseline that builds Embree's own
/// hierarchy (no restructuring, normal cones, width or front to combine with; it is checked against `sequential`
/// in test_schedulers.cpp).
inline std::vector<std::string> bvtt_schedulers() {
  std::vector<std::string> out;
  for (const std::string& s : scheduler_registry().names())
    if (s != "embree") out.push_back(s);
  return out;
}

}  // namespace ccdlab::test
