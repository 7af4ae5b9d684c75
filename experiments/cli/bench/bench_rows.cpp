#include "experiments/cli/bench/bench_rows.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "experiments/cli/report.hpp"

namespace ccdlab::cli {

nlohmann::ordered_json BenchRow::columns() const {
  return {{"scheduler", scheduler},
          {"threads", threads},
          {"ms_per_step", ms},
          {"ms_per_step_min", ms_min},
          {"ms_per_step_max", ms_max},
          {"speedup", speedup},
          {"speedup_min", speedup_min},
          {"bv_tests_per_step", bv_tests},
          {"lambda", lambda},
          {"candidates_per_step", candidates},
          {"elementary_tests_per_step", elementary_tests},
          {"traverse_ms_per_step", traverse_ms},
          {"serial_ms_per_step", serial_ms},
          {"imbalance", imbalance},
          {"front_nodes_max", front_nodes_max},
          {"front_bytes_max", front_bytes_max},
          {"sprouted_per_step", sprouted},
          {"pruned_per_step", pruned},
          {"rebuilds", rebuilds},
          {"round_spread", round_spread},
          {"hash", fmt::format("{:016x}", hash)}};
}

BenchRow bench_row(const BenchRun& run, const Measured& m, const Measured& reference, int steps) {
  BenchRow row;
  row.scheduler = run.label();
  row.threads = run.threads;
  row.ms = median(m.ms_per_step);
  row.ms_min = *std::min_element(m.ms_per_step.begin(), m.ms_per_step.end());
  row.ms_max = *std::max_element(m.ms_per_step.begin(), m.ms_per_step.end());
  row.speedup = median(reference.ms_per_step) / row.ms;
  row.speedup_min = *std::min_element(reference.ms_per_step.begin(), reference.ms_per_step.end()) / row.ms_min;
  row.bv_tests = m.bv_tests / steps;
  row.lambda = reference.bv_tests ? double(m.bv_tests) / double(reference.bv_tests) : 0;
  row.candidates = m.candidates / steps;
  row.elementary_tests = m.elementary_tests / steps;
  row.traverse_ms = m.traverse_ms / steps;
  row.serial_ms = m.serial_ms / steps;
  row.imbalance = m.imbalance_n ? m.imbalance_sum / m.imbalance_n : 0;
  row.front_nodes_max = m.front_max;
  row.front_bytes_max = m.front_bytes_max;
  row.sprouted = m.sprouted / steps;
  row.pruned = m.pruned / steps;
  row.rebuilds = m.rebuilds;
  row.round_spread = m.spread;
  row.hash = m.hash;
  return row;
}

std::string bench_csv_header() {
  std::string line;
  const nlohmann::ordered_json columns = BenchRow{}.columns();
  for (const auto& [name, value] : columns.items()) line += name + ",";
  return line + "git_revision\n";
}

std::string bench_csv_line(const BenchRow& row, const std::string& git_revision) {
  std::string line;
  const nlohmann::ordered_json columns = row.columns();
  for (const auto& [name, value] : columns.items()) {
    if (value.is_string()) line += value.get<std::string>();
    else if (value.is_number_float()) line += fmt::format("{:.4f}", value.get<double>());
    else line += value.dump();
    line += ",";
  }
  return line + git_revision + "\n";
}

void print_bench_header(std::FILE* out) {
  fmt::print(out, "{:>10} {:>3} {:>9} {:>7} {:>9} {:>7} {:>11} {:>6} {:>10} {:>9} {:>9} {:>9} {:>10}\n", "scheduler",
             "thr", "ms/step", "speedup", "min ms", "(min)", "BV tests", "lambda", "traverse", "serial", "imbal.", "front",
             "front MB");
}

void print_bench_row(std::FILE* out, const BenchRow& r) {
  fmt::print(out, "{:>10} {:>3} {:>9.2f} {:>6.2f}x {:>9.2f} {:>6.2f}x {:>11} {:>6.3f} {:>10.2f} {:>9.2f} {:>9.2f} {:>9} {:>10.2f}\n",
             r.scheduler, r.threads, r.ms, r.speedup, r.ms_min, r.speedup_min, r.bv_tests, r.lambda, r.traverse_ms,
             r.serial_ms, r.imbalance, r.front_nodes_max, r.front_bytes_max / 1e6);
}

}  // namespace ccdlab::cli
