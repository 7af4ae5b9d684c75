// `ccdlab bench CONFIG.yaml [--set k=v …] [--schedulers LIST] [--threads LIST] [--narrow LIST] [--rounds R]
//  [--cores LIST] [--untimed-steps K]`: every narrow mode × scheduler × thread count on the config's scene (a scalar narrow phase is
// labelled SCHEDULER/scalar), in alternating rounds (A B C …, then … C B A) so drift
// hits all alike; per configuration the median over rounds of the mean ms per step. Checks that every
// configuration found the identical contact sets (exit 1 otherwise), reports the counters that explain speed
// (BV tests and λ, front size, serial part, thread imbalance), and replays the recorded task costs of the
// 1-thread runs on N simulated cores (framework/pipeline/schedule_sim.hpp). Writes bench.csv, scaling.csv and
// bench.jsonl to output.dir.
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include <unistd.h>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/report.hpp"
#include "framework/pipeline/schedule_sim.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/progress.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {
namespace {

struct Config {
  std::string scheduler;
  int threads;
  NarrowMode narrow = NarrowMode::batched;
  /// > 0: a recording run — 1 thread, the BVTT split for `split` threads — whose task costs the simulator replays
  /// on `split` cores (phc and static cut c·threads tasks, so the 1-thread split would misrepresent them).
  /// Timed in the same alternating rounds, checked for the same hash, left out of the tables.
  int split = 0;
  /// How the configuration is named in tables and files: the scheduler, "/scalar" for the scalar narrow phase.
  [[nodiscard]] std::string label() const { return narrow == NarrowMode::batched ? scheduler : scheduler + "/scalar"; }
  [[nodiscard]] std::string name() const {
    return split ? fmt::format("{} x1 split for {}", label(), split) : fmt::format("{} x{}", label(), threads);
  }
};

struct Measured {
  std::vector<double> ms_per_step;  ///< one value per round: mean over steps
  std::uint64_t hash = 0;
  std::uint64_t bv_tests = 0, candidates = 0, elementary_tests = 0;
  std::uint64_t front_max = 0, front_bytes_max = 0, sprouted = 0, pruned = 0, rebuilds = 0;
  double serial_ms = 0, traverse_ms = 0, imbalance_sum = 0;
  double spread = 0;  ///< (max − min) ÷ median of the rounds' ms per step
  int imbalance_n = 0;
  std::vector<std::vector<std::vector<PhaseTrace>>> traces;  ///< per round, per step
  /// Traces of the round whose time is the median: the simulator replays a typical run, not an outlier.
  [[nodiscard]] const std::vector<std::vector<PhaseTrace>>& median_traces() const {
    std::vector<std::size_t> order(ms_per_step.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ms_per_step[a] < ms_per_step[b]; });
    return traces[order[order.size() / 2]];
  }
};

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

int bench_command(const BenchOptions& o) {
  const Registries reg = builtin_registries();
  ExperimentConfig config = load_experiment(o.config, o.overrides, reg);
  const std::vector<std::string> schedulers = parse_names(o.schedulers);
  for (const auto& s : schedulers)
    if (!reg.schedulers.find(s))
      fail("--schedulers: expected names from {}, got '{}'", fmt::join(reg.schedulers.names(), ", "), s);
  const std::vector<int> threads = parse_ints(o.threads, "threads", kMaxThreads);
  const std::vector<int> cores = parse_ints(o.cores, "cores", 1 << 20);
  if (o.rounds < 1) fail("--rounds: expected an integer >= 1, got {}", o.rounds);

  const MeshSequence scene = make_scene(config, reg);
  std::vector<Positions> frames;
  for (int f = 0; f < scene.num_frames(); ++f) frames.push_back(scene.frame(f));  // outside the timing
  const int all_steps = scene.num_steps();
  if (o.untimed_steps < 0 || o.untimed_steps >= all_steps)
    fail("--untimed-steps: expected an integer from 0 to {} (the scene has {} steps), got {}", all_steps - 1, all_steps,
         o.untimed_steps);
  const int steps = all_steps - o.untimed_steps;  // timed and counted per run

  std::vector<NarrowMode> narrow_modes;
  for (const auto& n : parse_names(o.narrow)) narrow_modes.push_back(kNarrowModes.parse(n, "--narrow"));
  std::vector<Config> configs;
  for (NarrowMode n : narrow_modes)
    for (const auto& s : schedulers)
      for (int t : threads) configs.push_back({s, t, n});
  // Recording runs for the simulator: a scheduler whose tasks depend on the thread count is recorded, on one
  // thread, split as each simulated core count would split it.
  const std::size_t measured_configs = configs.size();
  for (std::size_t i = 0; i < measured_configs; ++i) {
    if (configs[i].threads != 1) continue;
    if (!reg.schedulers.make({configs[i].scheduler, reg.schedulers.find(configs[i].scheduler)->defaults()})->splits_by_threads())
      continue;
    for (int n : cores)
      if (n > 1) configs.push_back({configs[i].scheduler, 1, configs[i].narrow, n});
  }
  std::vector<Measured> measured(configs.size());

  // The machine's fork/join cost, for the simulator (schedule_sim.hpp): measured on as many threads as both the
  // machine and the simulated cores have.
  const int probe_threads = std::max(1, std::min(int(std::thread::hardware_concurrency()), *std::max_element(cores.begin(), cores.end())));
  const MachineModel machine = probe_machine(probe_threads);
  // Round −1 warms caches, page tables and the OpenMP thread pools; it is not timed into any result.
  Progress progress("ccdlab bench", long((o.rounds + 1) * configs.size()), o.progress);
  long done = 0;
  for (int round = -1; round < o.rounds; ++round) {
    const bool warmup = round < 0;
    for (std::size_t j = 0; j < configs.size(); ++j) {
      const std::size_t i = round % 2 == 0 ? j : configs.size() - 1 - j;  // alternate the order
      ExperimentConfig c = config;
      c.scheduler = {configs[i].scheduler, reg.schedulers.find(configs[i].scheduler)->defaults()};
      if (config.scheduler.name == configs[i].scheduler) c.scheduler = config.scheduler;  // keep --set params
      c.threads = configs[i].threads;
      c.split_threads = configs[i].split;
      c.narrow.mode = configs[i].narrow;
      CcdPipeline pipeline(scene.topology(), scene.bodies(), make_strategies(c, reg));
      Measured& m = measured[i];
      double total = 0;
      std::uint64_t hash = contact_set_hash({});
      if (!warmup) m.traces.emplace_back();
      StepResult r;  // one for every step: its contact list's memory reused
      for (int s = 0; s < all_steps; ++s) {
        pipeline.step(frames[s], frames[s + 1], r);
        hash = contact_set_hash(r.contacts, hash);
        if (s < o.untimed_steps) continue;  // a steady state's first steps: the BVH built, a front grown
        total += r.timings.total_ms;
        if (warmup) continue;
        if (round == 0) {
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
        m.traces.back().push_back(std::move(r.traces));
      }
      if (warmup || round == 0) {
        if (round == 0 && hash != m.hash)
          fail("bench: {} changed its answer between the warm-up and round 1", configs[i].name());
        m.hash = hash;
      } else if (hash != m.hash) {
        fail("bench: {} changed its answer between rounds", configs[i].name());
      }
      if (!warmup) m.ms_per_step.push_back(total / steps);
      progress.update(++done);
    }
  }
  // Rounds of one configuration that disagree by more than the noise threshold make every ratio doubtful.
  constexpr double kNoiseThreshold = 0.10;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    const auto [lo, hi] = std::minmax_element(measured[i].ms_per_step.begin(), measured[i].ms_per_step.end());
    const double spread = (*hi - *lo) / median(measured[i].ms_per_step);
    measured[i].spread = spread;
    if (spread > kNoiseThreshold && i < measured_configs)  // recording runs feed the simulator only
      fmt::print(stderr, "ccdlab: warning: bench: {}: rounds differ by {:.0f}% ({:.3f} to {:.3f} ms/step), above the "
                 "{:.0f}% noise threshold: other load on the machine? more --rounds?\n",
                 configs[i].name(), 100 * spread, *lo, *hi, 100 * kNoiseThreshold);
  }

  // Reference: sequential at 1 thread (or the first configuration).
  std::size_t ref = configs.size();
  for (std::size_t i = 0; i < measured_configs; ++i)
    if (ref == configs.size() && configs[i].scheduler == "sequential" && configs[i].threads == 1) ref = i;
  if (ref == configs.size()) ref = 0;
  const double ref_ms = median(measured[ref].ms_per_step);
  const double ref_min = *std::min_element(measured[ref].ms_per_step.begin(), measured[ref].ms_per_step.end());
  bool identical = true;
  for (const Measured& m : measured) identical &= m.hash == measured[0].hash;

  namespace fs = std::filesystem;
  const std::string rev = build_info::git_revision;
  create_output_dir(config.output.dir, "output.dir");
  auto out_path = [&](const char* name) { return (fs::path(config.output.dir) / name).string(); };
  OutputFile csv(out_path("bench.csv"), "output.dir"), scaling(out_path("scaling.csv"), "output.dir"),
      jsonl(out_path("bench.jsonl"), "output.dir");
  const nlohmann::json config_json = to_json(config);
  jsonl << nlohmann::json{{"type", "config"}, {"config", config_json}, {"git_revision", rev}, {"scene", scene.description()},
                          {"triangles", scene.topology().num_faces()}, {"steps", steps}, {"untimed_steps", o.untimed_steps}, {"rounds", o.rounds},
                          {"cpu", cpu_model()}, {"hardware_threads", std::thread::hardware_concurrency()},
                          {"fork_join_ms", machine.fork_join_ms},
                          {"compiler", build_info::compiler}}
               .dump()
        << "\n";
  csv << "scheduler,threads,ms_per_step,ms_per_step_min,ms_per_step_max,speedup,speedup_min,bv_tests_per_step,lambda,candidates_per_step,elementary_tests_per_step,"
         "traverse_ms_per_step,serial_ms_per_step,imbalance,front_nodes_max,front_bytes_max,sprouted_per_step,"
         "pruned_per_step,rebuilds,hash,git_revision\n";
  scaling << "scheduler,cores,predicted_ms_per_step,predicted_speedup,measured_ms_per_step,ideal_ms_per_step\n";

  const std::uint64_t seq_bv = measured[ref].bv_tests;
  if (!o.json) {
    fmt::print("ccdlab bench {} — {}, {} steps{}, {} rounds (alternating), rev {}\n", config.name, scene.description(),
               steps, o.untimed_steps > 0 ? fmt::format(" timed after {} untimed", o.untimed_steps) : "", o.rounds, rev);
    fmt::print("k={} tester={}; speed-up against {} x{} = {:.2f} ms/step\n\n", config.k, config.tester.name,
               configs[ref].label(), configs[ref].threads, ref_ms);
    fmt::print("{:>10} {:>3} {:>9} {:>7} {:>9} {:>7} {:>11} {:>6} {:>10} {:>9} {:>9} {:>9} {:>10}\n", "scheduler", "thr",
               "ms/step", "speedup", "min ms", "(min)", "BV tests", "lambda", "traverse", "serial", "imbal.", "front", "front MB");
  }
  nlohmann::json out_rows = nlohmann::json::array();
  for (std::size_t i = 0; i < measured_configs; ++i) {
    const Measured& m = measured[i];
    const double ms = median(m.ms_per_step);
    const double ms_min = *std::min_element(m.ms_per_step.begin(), m.ms_per_step.end());
    const double ms_max = *std::max_element(m.ms_per_step.begin(), m.ms_per_step.end());
    const double lambda = seq_bv ? double(m.bv_tests) / double(seq_bv) : 0;
    const double imb = m.imbalance_n ? m.imbalance_sum / m.imbalance_n : 0;
    csv << fmt::format("{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{},{:.4f},{},{},{:.4f},{:.4f},{:.4f},{},{},{},{},{},{:016x},{}\n",
                       configs[i].label(), configs[i].threads, ms, ms_min, ms_max, ref_ms / ms, ref_min / ms_min,
                       m.bv_tests / steps, lambda,
                       m.candidates / steps, m.elementary_tests / steps, m.traverse_ms / steps, m.serial_ms / steps, imb,
                       m.front_max, m.front_bytes_max, m.sprouted / steps, m.pruned / steps, m.rebuilds, m.hash, rev);
    nlohmann::json row = {{"scheduler", configs[i].label()}, {"threads", configs[i].threads}, {"ms_per_step", ms},
                          {"ms_per_step_min", ms_min}, {"ms_per_step_max", ms_max}, {"speedup", ref_ms / ms}, {"speedup_min", ref_min / ms_min}, {"bv_tests_per_step", m.bv_tests / steps}, {"lambda", lambda},
                          {"traverse_ms_per_step", m.traverse_ms / steps}, {"serial_ms_per_step", m.serial_ms / steps},
                          {"imbalance", imb}, {"front_nodes_max", m.front_max}, {"front_bytes_max", m.front_bytes_max},
                          {"round_spread", m.spread}, {"hash", fmt::format("{:016x}", m.hash)}};
    out_rows.push_back(row);
    jsonl << nlohmann::json{{"type", "config_result"}, {"result", row}}.dump() << "\n";
    if (!o.json)
      fmt::print("{:>10} {:>3} {:>9.2f} {:>6.2f}x {:>9.2f} {:>6.2f}x {:>11} {:>6.3f} {:>10.2f} {:>9.2f} {:>9.2f} {:>9} {:>10.2f}\n",
                 configs[i].label(), configs[i].threads, ms, ref_ms / ms, ms_min, ref_min / ms_min, m.bv_tests / steps,
                 lambda,
                 m.traverse_ms / steps, m.serial_ms / steps, imb, m.front_max, m.front_bytes_max / 1e6);
  }

  // The machine model of each scheduler's 1-thread run: the probe's fork/join cost, and each phase's task
  // inflation measured between that run (split as the most threads measured would split it) and the run on
  // that many threads. None where no multi-thread run was measured.
  const int most_threads = *std::max_element(threads.begin(), threads.end());
  std::vector<MachineModel> machine_of(measured_configs, machine);
  for (std::size_t i = 0; i < measured_configs; ++i) {
    if (configs[i].threads != 1 || most_threads < 2) continue;
    std::size_t alone = i, parallel = i;
    for (std::size_t j = 0; j < configs.size(); ++j) {
      if (configs[j].label() != configs[i].label()) continue;
      if (j >= measured_configs && configs[j].split == most_threads) alone = j;
      if (j < measured_configs && configs[j].threads == most_threads) parallel = j;
    }
    if (parallel != i)
      machine_of[i].task_inflation = measure_task_inflation(measured[alone].median_traces(), measured[parallel].median_traces());
  }

  // Simulated scaling from the 1-thread task costs; validated where a measured run exists.
  nlohmann::json sim_rows = nlohmann::json::array();
  if (!o.json) {
    std::vector<std::string> fork_join_us;
    for (double ms : machine.fork_join_ms) fork_join_us.push_back(fmt::format("{:.1f}", 1e3 * ms));
    fmt::print("\nsimulated ms/step (speed-up vs {} x1) from 1-thread task costs, with this machine's fork/join ({} us on\n"
               "1..{} threads) and each phase's task inflation at {} threads; [measured, error (ideal machine's error)]:\n",
               configs[ref].label(), fmt::join(fork_join_us, "/"), probe_threads, most_threads);
  }
  for (std::size_t i = 0; i < measured_configs; ++i) {
    if (configs[i].threads != 1) continue;
    const MachineModel& machine = machine_of[i];
    std::string line = fmt::format("{:>10}", configs[i].label());
    for (int n : cores) {
      std::size_t recorded = i;  // the run split for n threads, where the scheduler's split depends on it
      for (std::size_t j = measured_configs; j < configs.size(); ++j)
        if (configs[j].label() == configs[i].label() && configs[j].split == n) recorded = j;
      double predicted = 0, ideal = 0;
      for (const auto& step_traces : measured[recorded].median_traces()) {
        predicted += simulate_step(step_traces, n, &machine);
        ideal += simulate_step(step_traces, n);
      }
      predicted /= steps;
      ideal /= steps;
      double measured_ms = -1;
      for (std::size_t j = 0; j < measured_configs; ++j)
        if (configs[j].label() == configs[i].label() && configs[j].threads == n) measured_ms = median(measured[j].ms_per_step);
      scaling << fmt::format("{},{},{:.4f},{:.4f},{},{:.4f}\n", configs[i].label(), n, predicted, ref_ms / predicted,
                             measured_ms < 0 ? std::string() : fmt::format("{:.4f}", measured_ms), ideal);
      sim_rows.push_back({{"scheduler", configs[i].label()}, {"cores", n}, {"predicted_ms_per_step", predicted},
                          {"predicted_speedup", ref_ms / predicted}, {"ideal_ms_per_step", ideal},
                          {"measured_ms_per_step", measured_ms < 0 ? nlohmann::json() : nlohmann::json(measured_ms)}});
      line += measured_ms < 0 ? fmt::format(" | {}: {:.2f} ({:.2f}x)", n, predicted, ref_ms / predicted)
                              : fmt::format(" | {}: {:.2f} ({:.2f}x) [{:.2f}, {:+.0f}% ({:+.0f}%)]", n, predicted,
                                            ref_ms / predicted, measured_ms, 100 * (predicted - measured_ms) / measured_ms,
                                            100 * (ideal - measured_ms) / measured_ms);
    }
    if (!o.json) fmt::print("{}\n", line);
  }
  jsonl << nlohmann::json{{"type", "scaling"}, {"rows", sim_rows}}.dump() << "\n";

  // Where scaling stops: per phase, ms/step on 1 core and on the largest simulated core count ≤ 8 (or the max).
  int probe = cores.front();
  for (int n : cores)
    if (n <= 8) probe = std::max(probe, n);
  if (!o.json)
    fmt::print("\nper phase, ms/step at 1 core -> {} simulated cores (serial part, task inflation); the serial fraction of a step:\n", probe);
  for (std::size_t i = 0; i < measured_configs; ++i) {
    if (configs[i].threads != 1) continue;
    std::map<std::string, std::array<double, 3>> phases;  // 1 core, N cores, serial
    std::size_t recorded = i;
    for (std::size_t j = measured_configs; j < configs.size(); ++j)
      if (configs[j].label() == configs[i].label() && configs[j].split == probe) recorded = j;
    for (const auto& step_traces : measured[i].median_traces())
      for (const PhaseTrace& t : step_traces) phases[t.phase][0] += simulate_phase(t, 1, &machine) / steps;
    for (const auto& step_traces : measured[recorded].median_traces())
      for (const PhaseTrace& t : step_traces) {
        auto& acc = phases[t.phase];
        acc[1] += simulate_phase(t, probe, &machine) / steps;
        acc[2] += t.serial_ms / steps;
      }
    const MachineModel& machine = machine_of[i];
    nlohmann::json row = {{"type", "phases"}, {"scheduler", configs[i].label()}, {"cores", probe},
                          {"task_inflation", machine.task_inflation}};
    std::string line = fmt::format("{:>10}", configs[i].label());
    double one_core = 0, serial = 0;
    for (const auto& [name, acc] : phases) {
      row["phases"][name] = {{"ms_1", acc[0]}, {"ms_n", acc[1]}, {"serial_ms", acc[2]}};
      const double inflation = machine.inflation(name, probe);
      line += fmt::format(" | {} {:.1f}->{:.1f} ({:.1f}{})", name, acc[0], acc[1], acc[2],
                          inflation != 1 ? fmt::format(", tasks x{:.2f}", inflation) : std::string());
      one_core += acc[0], serial += acc[2];
    }
    // The serial fraction of a step (every phase's part outside its parallel loop, and the phases without one):
    // Amdahl's bound on the speed-up, whatever the cores.
    const double fraction = one_core > 0 ? serial / one_core : 0;
    row["serial_fraction"] = fraction;
    line += fmt::format(" || serial {:.2f} of {:.1f} ms = {:.1f}% (Amdahl bound {})", serial, one_core, 100 * fraction,
                        fraction > 0 ? fmt::format("{:.0f}x", 1 / fraction) : std::string("none"));
    jsonl << row.dump() << "\n";
    if (!o.json) fmt::print("{}\n", line);
  }
  if (o.json)
    fmt::print("{}\n", nlohmann::json{{"configs", out_rows}, {"scaling", sim_rows}, {"identical", identical},
                                      {"reference_ms_per_step", ref_ms}, {"steps", steps}, {"git_revision", rev}}
                           .dump(2));
  else
    fmt::print("\ncontact sets identical across all configurations: {} (hash {:016x})\nresults in {}/\n",
               identical ? "yes" : "NO", measured[0].hash, config.output.dir);
  csv.commit();
  scaling.commit();
  jsonl.commit();
  return identical ? 0 : 1;
}

}  // namespace ccdlab::cli
