#include "experiments/cli/bench/bench_measure.hpp"

#include <algorithm>

#include "experiments/cli/report.hpp"
#include "framework/pipeline/schedule_sim.hpp"
#include "framework/util/error.hpp"
#include "framework/util/progress.hpp"

namespace ccdlab::cli {

const std::vector<std::vector<PhaseTrace>>& Measured::median_traces() const {
  std::vector<std::size_t> order(ms_per_step.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ms_per_step[a] < ms_per_step[b]; });
  return traces[order[order.size() / 2]];
}

namespace {

/// The first round's counters of one step.
void count(const StepResult& r, Measured& m) {
  m.bv_tests += r.counters.bv_tests;
  m.candidates += r.counters.candidate_pairs;
  m.elementary_tests += r.counters.vf_tests + r.counters.ee_tests;
  m.front_max = std::max(m.front_max, r.traversal.front_nodes);
  m.front_bytes_max = std::max(m.front_bytes_max, r.traversal.front_bytes);
  m.sprouted += r.traversal.sprouted;
  m.pruned += r.traversal.pruned;
  m.rebuilds += r.traversal.rebuilds;
  m.serial_ms += r.traversal.serial_ms;
  m.traverse_ms += r.timings.traverse_ms;
  for (const PhaseTrace& t : r.traces)
    if (t.phase == "traverse" && !t.thread_ms.empty()) m.imbalance_sum += imbalance(t), ++m.imbalance_n;
}

}  // namespace

std::vector<Measured> measure_bench(const BenchPlan& plan, const ExperimentConfig& config, const Registries& reg,
                                    const MeshSequence& scene, const std::vector<Positions>& frames, bool show_progress) {
  const int all_steps = scene.num_steps(), steps = all_steps - plan.untimed_steps;
  std::vector<Measured> measured(plan.runs.size());
  // Round −1 warms caches, page tables and the OpenMP thread pools; it is not timed into any result.
  Progress progress("ccdlab bench", long((plan.rounds + 1) * plan.runs.size()), show_progress);
  long done = 0;
  for (int round = -1; round < plan.rounds; ++round) {
    const bool warmup = round < 0;
    for (std::size_t j = 0; j < plan.runs.size(); ++j) {
      const std::size_t i = round % 2 == 0 ? j : plan.runs.size() - 1 - j;  // alternate the order
      const BenchRun& run = plan.runs[i];
      ExperimentConfig c = config;
      c.scheduler = {run.scheduler, reg.schedulers.find(run.scheduler)->defaults()};
      if (config.scheduler.name == run.scheduler) c.scheduler = config.scheduler;  // keep --set params
      c.threads = run.threads;
      c.split_threads = run.split;
      c.narrow.mode = run.narrow;
      CcdPipeline pipeline(scene.topology(), scene.bodies(), make_strategies(c, reg));
      Measured& m = measured[i];
      double total = 0;
      std::uint64_t hash = contact_set_hash({});
      if (!warmup) m.traces.emplace_back();
      StepResult r;  // one for every step: its contact list's memory reused
      for (int s = 0; s < all_steps; ++s) {
        pipeline.step(frames[s], frames[s + 1], r);
        hash = contact_set_hash(r.contacts, hash);
        if (s < plan.untimed_steps) continue;  // a steady state's first steps: the BVH built, a front grown
        total += r.timings.total_ms;
        if (warmup) continue;
        if (round == 0) count(r, m);
        m.traces.back().push_back(std::move(r.traces));
      }
      if (warmup || round == 0) {
        if (round == 0 && hash != m.hash) fail("bench: {} changed its answer between the warm-up and round 1", run.name());
        m.hash = hash;
      } else if (hash != m.hash) {
        fail("bench: {} changed its answer between rounds", run.name());
      }
      if (!warmup) m.ms_per_step.push_back(total / steps);
      progress.update(++done);
    }
  }
  return measured;
}

void check_round_spread(const BenchPlan& plan, std::vector<Measured>& measured) {
  // Rounds of one configuration that disagree by more than this make every ratio doubtful.
  constexpr double kNoiseThreshold = 0.10;
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const auto [lo, hi] = std::minmax_element(measured[i].ms_per_step.begin(), measured[i].ms_per_step.end());
    const double spread = (*hi - *lo) / median(measured[i].ms_per_step);
    measured[i].spread = spread;
    if (spread > kNoiseThreshold && i < plan.measured)  // recording runs feed the simulator only
      fmt::print(stderr, "ccdlab: warning: bench: {}: rounds differ by {:.0f}% ({:.3f} to {:.3f} ms/step), above the "
                 "{:.0f}% noise threshold: other load on the machine? more --rounds?\n",
                 plan.runs[i].name(), 100 * spread, *lo, *hi, 100 * kNoiseThreshold);
  }
}

}  // namespace ccdlab::cli
