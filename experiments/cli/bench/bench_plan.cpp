#include "experiments/cli/bench/bench_plan.hpp"

#include <stdexcept>

#include "framework/util/error.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab::cli {
namespace {

std::vector<int> parse_ints(const std::string& list, const char* option, int max) {
  std::vector<int> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t comma = list.find(',', start);
    std::string item = list.substr(start, comma - start);
    try {
      std::size_t used = 0;
      int v = std::stoi(item, &used);
      if (used != item.size() || v < 1 || v > max) throw std::invalid_argument(item);
      out.push_back(v);
    } catch (const std::exception&) {
      fail("--{}: expected a comma-separated list of integers from 1 to {}, got '{}'", option, max, list);
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<std::string> parse_names(const std::string& list) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    std::size_t comma = list.find(',', start);
    out.push_back(list.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

std::string BenchRun::name() const {
  return split ? fmt::format("{} x1 split for {}", label(), split) : fmt::format("{} x{}", label(), threads);
}

std::size_t BenchPlan::recorded(std::size_t measured_run, int n) const {
  for (std::size_t j = measured; j < runs.size(); ++j)
    if (runs[j].label() == runs[measured_run].label() && runs[j].split == n) return j;
  return measured_run;
}

std::size_t BenchPlan::find(const std::string& label, int t) const {
  for (std::size_t j = 0; j < measured; ++j)
    if (runs[j].label() == label && runs[j].threads == t) return j;
  return measured;
}

BenchPlan plan_bench(const BenchOptions& o, const Registries& reg, int scene_steps) {
  BenchPlan plan;
  const std::vector<std::string> schedulers = parse_names(o.schedulers);
  for (const auto& s : schedulers)
    if (!reg.schedulers.find(s))
      fail("--schedulers: expected names from {}, got '{}'", fmt::join(reg.schedulers.names(), ", "), s);
  plan.threads = parse_ints(o.threads, "threads", kMaxThreads);
  plan.cores = parse_ints(o.cores, "cores", 1 << 20);
  if (o.rounds < 1) fail("--rounds: expected an integer >= 1, got {}", o.rounds);
  plan.rounds = o.rounds;
  if (o.untimed_steps < 0 || o.untimed_steps >= scene_steps)
    fail("--untimed-steps: expected an integer from 0 to {} (the scene has {} steps), got {}", scene_steps - 1,
         scene_steps, o.untimed_steps);
  plan.untimed_steps = o.untimed_steps;

  for (const auto& n : parse_names(o.narrow)) {
    const NarrowMode mode = kNarrowModes.parse(n, "--narrow");
    for (const auto& s : schedulers)
      for (int t : plan.threads) plan.runs.push_back({s, t, mode});
  }
  plan.measured = plan.runs.size();
  // Recording runs for the simulator: a scheduler whose tasks depend on the thread count is recorded, on one
  // thread, split as each simulated core count would split it.
  for (std::size_t i = 0; i < plan.measured; ++i) {
    const BenchRun run = plan.runs[i];
    if (run.threads != 1) continue;
    if (!reg.schedulers.make({run.scheduler, reg.schedulers.find(run.scheduler)->defaults()})->splits_by_threads()) continue;
    for (int n : plan.cores)
      if (n > 1) plan.runs.push_back({run.scheduler, 1, run.narrow, n});
  }
  plan.reference = 0;
  for (std::size_t i = plan.measured; i-- > 0;)
    if (plan.runs[i].scheduler == "sequential" && plan.runs[i].threads == 1) plan.reference = i;
  return plan;
}

}  // namespace ccdlab::cli
