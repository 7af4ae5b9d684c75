#pragma once
// Runs a tester over a query set and scores it against the ground truth (and an exact time-of-contact
// reference): what `ccdlab validate` prints and the accuracy tests assert.
#include <cstdint>
#include <string>
#include <vector>

#include "framework/primitive/tester.hpp"
#include "framework/queries/query_set.hpp"

namespace ccdlab {

/// One tester's answer to one query, and its time (the fastest of `repeat` runs, in µs).
struct QueryOutcome {
  bool hit = false;
  double toi = 1.0;
  TestRoute route = TestRoute::main;
  double us = 0;
};

/// The exact time of contact of a query: toi_lo ≤ t ≤ toi_hi (hit == false: no contact).
struct ToiReference {
  bool hit = false;
  double toi_lo = 1.0, toi_hi = 1.0;
};

std::vector<QueryOutcome> run_tester(const PrimitiveTester& tester, const QuerySet& set, int repeat = 1);

struct SetScore {
  std::string set, tester;
  std::string scene, collection;  ///< of the set (QuerySet)
  std::size_t queries = 0, positives = 0;
  std::size_t false_negatives = 0, false_positives = 0;
  std::size_t filtered = 0, fallbacks = 0;  ///< decided by a filter / by the fallback (TestRoute)
  double mean_us = 0, median_us = 0, p99_us = 0, max_us = 0;
  /// |toi − exact| over queries both call a hit (exact: the width of its enclosing interval), and the number
  /// of hits whose toi is later than the exact one (a conservative tester must report none).
  double toi_max_error = 0, toi_mean_error = 0;
  std::size_t toi_late = 0;
  std::vector<std::size_t> failures;  ///< indices of the false negatives and false positives
};

/// Scores outcomes against `set.truth`; `reference` (same size, may be empty) gives the exact times.
SetScore score(const QuerySet& set, const std::string& tester, const std::vector<QueryOutcome>& outcomes,
               const std::vector<ToiReference>& reference);

}  // namespace ccdlab
