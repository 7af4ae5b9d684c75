#pragma once
// `ccdlab bench`, step 3 of 4: one row per reported run, its columns named once (BenchRow::columns) for all three
// writers — bench.csv, bench.jsonl and the --json summary — and the terminal table.
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "experiments/cli/bench/bench_measure.hpp"

namespace ccdlab::cli {

struct BenchRow {
  std::string scheduler;  ///< the run's label
  int threads = 1;
  double ms = 0, ms_min = 0, ms_max = 0;  ///< per step: the median, fastest and slowest round
  double speedup = 0, speedup_min = 0;    ///< against the plan's reference run (median; fastest rounds)
  std::uint64_t bv_tests = 0, candidates = 0, elementary_tests = 0;  ///< per step
  double lambda = 0;                      ///< BV tests ÷ the reference's
  double traverse_ms = 0, serial_ms = 0, imbalance = 0;
  std::uint64_t front_nodes_max = 0, front_bytes_max = 0, sprouted = 0, pruned = 0, rebuilds = 0;
  double round_spread = 0;
  std::uint64_t hash = 0;

  /// The columns, in file order, with their values: bench.csv's header and line, bench.jsonl's and --json's rows.
  [[nodiscard]] nlohmann::ordered_json columns() const;
};

BenchRow bench_row(const BenchRun& run, const Measured& m, const Measured& reference, int steps);

/// bench.csv's header line and one row's line (numbers as the files have always written them; git_revision last).
std::string bench_csv_header();
std::string bench_csv_line(const BenchRow& row, const std::string& git_revision);

/// The terminal table: its header, and one row.
void print_bench_header(std::FILE* out);
void print_bench_row(std::FILE* out, const BenchRow& row);

}  // namespace ccdlab::cli
