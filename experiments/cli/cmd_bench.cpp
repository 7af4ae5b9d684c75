// `ccdlab bench CONFIG.yaml [--set k=v …] [--schedulers LIST] [--threads LIST] [--narrow LIST] [--rounds R]
//  [--cores LIST] [--untimed-steps K]`: every narrow mode × scheduler × thread count on the config's scene (a scalar narrow phase is
// labelled SCHEDULER/scalar), in alternating rounds (A B C …, then … C B A) so drift
// hits all alike; per configuration the median over rounds of the mean ms per step. Checks that every
// configuration found the identical contact sets (exit 1 otherwise), reports the counters that explain speed
// (BV tests and λ, front size, serial part, thread imbalance), and replays the recorded task costs of the
// 1-thread runs on N simulated cores (framework/pipeline/schedule_sim.hpp). Writes bench.csv, scaling.csv and
// bench.jsonl to output.dir. The four steps have a file each in experiments/cli/bench/: plan, measure, rows,
// simulate; this file runs them and writes the results.
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include <unistd.h>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/bench/bench_measure.hpp"
#include "experiments/cli/bench/bench_plan.hpp"
#include "experiments/cli/bench/bench_rows.hpp"
#include "experiments/cli/bench/bench_simulate.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/report.hpp"
#include "framework/pipeline/schedule_sim.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/progress.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {

int bench_command(const BenchOptions& o) {
  const Registries reg = builtin_registries();
  const ExperimentConfig config = load_experiment(o.config, o.overrides, reg);
  const MeshSequence scene = make_scene(config, reg);
  const BenchPlan plan = plan_bench(o, reg, scene.num_steps());
  std::vector<Positions> frames;
  for (int f = 0; f < scene.num_frames(); ++f) frames.push_back(scene.frame(f));  // outside the timing
  const int steps = scene.num_steps() - plan.untimed_steps;  // timed and counted per run

  // The machine's fork/join cost, for the simulator (schedule_sim.hpp): measured on as many threads as both the
  // machine and the simulated cores have.
  const int probe_threads =
      std::max(1, std::min(int(std::thread::hardware_concurrency()), *std::max_element(plan.cores.begin(), plan.cores.end())));
  const MachineModel machine = probe_machine(probe_threads);
  std::vector<Measured> measured = measure_bench(plan, config, reg, scene, frames, o.progress);
  check_round_spread(plan, measured);
  bool identical = true;
  for (const Measured& m : measured) identical &= m.hash == measured[0].hash;

  namespace fs = std::filesystem;
  const std::string rev = build_info::git_revision;
  create_output_dir(config.output.dir, "output.dir");
  auto out_path = [&](const char* name) { return (fs::path(config.output.dir) / name).string(); };
  OutputFile csv(out_path("bench.csv"), "output.dir"), scaling(out_path("scaling.csv"), "output.dir"),
      jsonl(out_path("bench.jsonl"), "output.dir");
  jsonl << nlohmann::json{{"type", "config"}, {"config", to_json(config)}, {"git_revision", rev}, {"scene", scene.description()},
                          {"triangles", scene.topology().num_faces()}, {"steps", steps}, {"untimed_steps", plan.untimed_steps},
                          {"rounds", plan.rounds}, {"cpu", cpu_model()}, {"hardware_threads", std::thread::hardware_concurrency()},
                          {"fork_join_ms", machine.fork_join_ms}, {"compiler", build_info::compiler}}
               .dump()
        << "\n";
  csv << bench_csv_header();
  scaling << "scheduler,cores,predicted_ms_per_step,predicted_speedup,measured_ms_per_step,ideal_ms_per_step\n";

  const Measured& reference = measured[plan.reference];
  const double ref_ms = median(reference.ms_per_step);
  if (!o.json) {
    fmt::print("ccdlab bench {} — {}, {} steps{}, {} rounds (alternating), rev {}\n", config.name, scene.description(),
               steps, plan.untimed_steps > 0 ? fmt::format(" timed after {} untimed", plan.untimed_steps) : "", plan.rounds, rev);
    fmt::print("k={} tester={}; speed-up against {} x{} = {:.2f} ms/step\n\n", config.k, config.tester.name,
               plan.runs[plan.reference].label(), plan.runs[plan.reference].threads, ref_ms);
    print_bench_header(stdout);
  }
  nlohmann::ordered_json out_rows = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < plan.measured; ++i) {
    const BenchRow row = bench_row(plan.runs[i], measured[i], reference, steps);
    csv << bench_csv_line(row, rev);
    out_rows.push_back(row.columns());
    jsonl << nlohmann::ordered_json{{"type", "config_result"}, {"result", row.columns()}}.dump() << "\n";
    if (!o.json) print_bench_row(stdout, row);
  }

  const BenchSimulation simulation{plan, measured, machine, probe_threads, steps, !o.json};
  const nlohmann::json sim_rows = simulation.scaling(scaling);
  jsonl << nlohmann::json{{"type", "scaling"}, {"rows", sim_rows}}.dump() << "\n";
  simulation.phases(jsonl);
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
