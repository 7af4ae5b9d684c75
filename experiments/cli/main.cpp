// ccdlab: command-line entry point. Subcommands: run, sweep, step, proximity, bench, simulate, export, validate, list, info
// (see README.md and docs/cli.md).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string_view>

#include "ccdlab/build_info.hpp"
#include "framework/util/simd_target.hpp"
#include "experiments/cli/commands.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"

namespace {

// Exit codes (README): 0 success, 1 a check failed (validate --check, bench answers differ), 2 a user error
// (bad flag, value, file or config: one "ccdlab: error: …" line), 3 an internal failure (a bug: please report).
constexpr int kUserError = 2;
constexpr int kInternalError = 3;

int user_error(std::string_view message) {
  fmt::print(stderr, "ccdlab: error: {}\n", message);
  return kUserError;
}

/// The pipeline's settings as flags of `cmd` (step, proximity): one per row of the settings table, less those the
/// command does not take (`skip`: members).
void add_setting_flags(CLI::App* cmd, ccdlab::cli::PipelineFlags& f, std::initializer_list<std::string_view> skip = {}) {
  const ccdlab::PipelineConfig defaults = ccdlab::default_config(ccdlab::builtin_registries());
  for (const ccdlab::Setting& s : ccdlab::settings()) {
    if (std::find(skip.begin(), skip.end(), s.member) != skip.end()) continue;
    std::string& text = f.texts.emplace_back();
    const std::string doc = fmt::format("{} (accepts {})", s.doc, s.accepts(ccdlab::builtin_registries()));
    // A flag whose column gives a bare value ({on}) is a flag that may take a value: --end-boxes, --end-boxes=off.
    CLI::Option* opt = s.flag.find('{') != std::string_view::npos ? cmd->add_flag(std::string(s.flag), text, doc)
                                                                  : cmd->add_option(std::string(s.flag), text, doc);
    opt->type_name(s.kind == ccdlab::SettingKind::strategy ? "NAME[:K=V,…]"
                   : s.kind == ccdlab::SettingKind::choice ? "NAME"
                   : s.kind == ccdlab::SettingKind::memory ? "SIZE"
                   : s.type == "int"                        ? "INT"
                   : s.type == "double"                     ? "NUMBER"
                                                            : "");
    opt->default_str(std::visit([](const auto& v) { return fmt::format("{}", v); }, s.value(defaults)));
    f.options.emplace_back(&s, opt);
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace ccdlab::cli;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // table rows reach a log or pipe as they are printed
  if (const char* simd = std::getenv("CCDLAB_SIMD")) {  // e.g. CCDLAB_SIMD=avx2: what each SIMD target buys
    try {
      ccdlab::limit_simd_target(simd);
    } catch (const ccdlab::Error& e) {
      return user_error(e.what());
    }
  }
  CLI::App app{"ccdlab: continuous collision detection for deforming cloth"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("ccdlab ") + ccdlab::build_info::git_revision);

  RunOptions run;
  bool no_progress = false;
  auto* run_cmd = app.add_subcommand("run", "run a YAML experiment: per-step table, CSV/JSONL results");
  run_cmd->add_option("config", run.config, "experiment YAML file")->required();
  run_cmd->add_option("--set", run.overrides, "override a config key, e.g. --set bv.k=26 (repeatable)");
  run_cmd->add_flag("--json", run.json, "print one JSON summary instead of the table");
  run_cmd->add_flag("--no-progress", no_progress, "no progress line on stderr");

  SweepOptions sweep;
  bool sweep_no_progress = false;
  auto* sweep_cmd = app.add_subcommand("sweep", "run every combination of a YAML sweep (resumable, shardable), or "
                                                 "merge the finished runs into runs.csv");
  sweep_cmd->add_option("config", sweep.config, "experiment YAML file with a sweep: block")->required();
  sweep_cmd->add_option("--set", sweep.overrides, "override a config key in every run (repeatable)");
  sweep_cmd->add_option("--shard", sweep.shard, "run only shard i of n (runs whose index mod n = i), e.g. 0/4")
      ->capture_default_str();
  sweep_cmd->add_flag("--dry-run", sweep.dry_run, "list the runs (index, shard, done or not, folder) and run nothing");
  sweep_cmd->add_flag("--force", sweep.force, "run again the runs whose folder already holds a complete result");
  sweep_cmd->add_flag("--merge", sweep.merge, "gather every finished run into runs.csv in output.dir; run nothing");
  sweep_cmd->add_flag("--no-progress", sweep_no_progress, "no progress line on stderr");

  StepOptions step;
  auto* step_cmd = app.add_subcommand("step", "one CCD step between two mesh files (PLY or OBJ)");
  step_cmd->add_option("t0", step.mesh_t0, "mesh at the start of the step")->required();
  step_cmd->add_option("t1", step.mesh_t1, "mesh at the end of the step (same topology)")->required();
  add_setting_flags(step_cmd, step);
  bool step_no_progress = false;
  step_cmd->add_flag("--no-progress", step_no_progress, "no progress line on stderr while a long step runs");
  step_cmd->add_option("--contacts", step.contacts_csv, "write contacts to this CSV (kind,a,b,c,d,toi,u,v,nx,ny,nz)");
  step_cmd->add_flag("--json", step.json, "print JSON instead of the table");
  step_cmd->add_flag("--earliest", step.earliest, "only the earliest time of contact (1 when none; JSON: earliest_toi), "
                     "skipping the pairs that cannot beat the best time found");

  ProximityOptions proximity;
  auto* proximity_cmd = app.add_subcommand("proximity", "every vertex-face and edge-edge pair closer than --dhat in one "
                                           "mesh file: distance and closest-feature type (a barrier solver's active set)");
  proximity_cmd->add_option("mesh", proximity.mesh, "mesh file (PLY or OBJ)")->required();
  proximity_cmd->add_option("--dhat", proximity.dhat, "the distance: pairs closer than it are reported")->required();
  proximity_cmd->add_flag("--relative", proximity.relative, "--dhat is a fraction of the mesh's bounding-box diagonal");
  add_setting_flags(proximity_cmd, proximity, {"tester", "normal_cones"});
  proximity_cmd->add_option("--repeat", proximity.repeat, "queries on the same positions (the first builds the hierarchy, "
                            "the others refit it): ms of the first and median of the others")->capture_default_str();
  proximity_cmd->add_flag("--check", proximity.check, "also find the pairs without the hierarchy (a sweep over boxes, the "
                          "same exact test: the reference and baseline), time it, exit 1 unless both find the same pairs");
  bool proximity_no_progress = false;
  proximity_cmd->add_flag("--no-progress", proximity_no_progress, "no progress line on stderr while a long query runs");
  proximity_cmd->add_option("--pairs", proximity.pairs_csv, "write the pairs to this CSV (kind,a,b,c,d,distance,type,u,v)");
  proximity_cmd->add_flag("--json", proximity.json, "print JSON instead of the summary");

  BenchOptions bench;
  bool bench_no_progress = false;
  auto* bench_cmd = app.add_subcommand("bench", "schedulers x threads in alternating rounds; counters; simulated scaling");
  bench_cmd->add_option("config", bench.config, "experiment YAML file (scene, k, tester, output.dir)")->required();
  bench_cmd->add_option("--set", bench.overrides, "override a config key (repeatable)");
  bench_cmd->add_option("--schedulers", bench.schedulers, "comma-separated schedulers")->capture_default_str();
  bench_cmd->add_option("--narrow", bench.narrow, "comma-separated narrow modes: batched, scalar (side by side)")
      ->capture_default_str();
  bench_cmd->add_option("--threads", bench.threads, "comma-separated thread counts")->capture_default_str();
  bench_cmd->add_option("--cores", bench.cores, "simulated core counts")->capture_default_str();
  bench_cmd->add_option("--rounds", bench.rounds, "alternating rounds")->capture_default_str();
  bench_cmd->add_option("--untimed-steps", bench.untimed_steps,
                        "run and check the first K steps of every run without timing them (a steady state)")
      ->capture_default_str();
  bench_cmd->add_flag("--json", bench.json, "print one JSON object instead of the tables");
  bench_cmd->add_flag("--no-progress", bench_no_progress, "no progress line on stderr");

  SimulateOptions simulate;
  bool simulate_no_progress = false;
  auto* simulate_cmd = app.add_subcommand("simulate", "simulate a scene with only the effects it lists; frames as PLY + meta.json");
  simulate_cmd->add_option("scene", simulate.scene, "scene YAML file (experiments/scenes/)")->required();
  simulate_cmd->add_option("--set", simulate.overrides, "override a scene key: frames=8, resolution=0.1, threads=2 (repeatable)");
  simulate_cmd->add_option("--out", simulate.out, "folder for the frames (default: results/scenes/NAME-HASH)");
  simulate_cmd->add_flag("--force", simulate.force, "simulate even when the folder holds this scene's frames");
  simulate_cmd->add_flag("--no-progress", simulate_no_progress, "no progress line on stderr");

  ExportOptions export_opts;
  bool export_no_progress = false;
  auto* export_cmd = app.add_subcommand("export", "VTK files for ParaView / meshio: mesh per frame with contact counts, "
                                        "BVH levels as k-DOP polyhedra, the BVTT front, the contacts");
  export_cmd->add_option("config", export_opts.config, "experiment YAML file")->required();
  export_cmd->add_option("--set", export_opts.overrides, "override a config key (repeatable)");
  export_cmd->add_option("--step", export_opts.step, "the step drawn in detail (default: the one with the most contacts)");
  export_cmd->add_option("--levels", export_opts.levels, "BVH depths to draw, from the root")->capture_default_str();
  export_cmd->add_option("--out", export_opts.out, "folder for the .vtu / .pvd files")->required();
  export_cmd->add_flag("--no-progress", export_no_progress, "no progress line on stderr");

  ValidateOptions validate;
  bool validate_no_progress = false;
  auto* validate_cmd = app.add_subcommand("validate", "testers against elementary query sets with known answers");
  validate_cmd->add_option("paths", validate.paths, "query CSV files or folders (../shared/data/ccd-queries), or hard-cases")->required();
  validate_cmd->add_option("--tester", validate.testers, "tester, e.g. float or conservative:delta=1e-4,fallback=exact (repeatable)")
      ->capture_default_str();
  validate_cmd->add_option("--repeat", validate.repeat, "time each query this many times, keep the fastest")->capture_default_str();
  validate_cmd->add_option("--out", validate.out_dir, "write validate.csv, validate.jsonl and queries.csv (per query) into this folder");
  validate_cmd->add_option("--failures", validate.failures, "list up to N wrong answers per tester and set");
  validate_cmd->add_flag("--check", validate.check, "exit 1 if exact disagrees with the truth or conservative misses");
  validate_cmd->add_flag("--json", validate.json, "print JSON instead of the table");
  validate_cmd->add_flag("--no-progress", validate_no_progress, "no progress line on stderr");

  auto* list_cmd = app.add_subcommand("list", "the settings, and the registered strategies and their parameters");
  bool settings_table = false;
  list_cmd->add_flag("--settings", settings_table, "print the settings table (docs/config.md's) as Markdown");
  auto* info_cmd = app.add_subcommand("info", "compiler, flags, OpenMP, git revision");

  // An unknown command is named (CLI11 would only say that a subcommand is required).
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    if (std::find(names.begin(), names.end(), argv[1]) == names.end())
      return user_error(fmt::format("unknown command '{}', expected one of {} (ccdlab --help)", ccdlab::printable(argv[1]),
                                    fmt::join(names, ", ")));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    return app.exit(CLI::CallForHelp());
  } catch (const CLI::CallForAllHelp&) {
    return app.exit(CLI::CallForAllHelp());
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Every other parse failure (unknown flag, missing argument, a value that does not convert) is a user error.
    const CLI::App* sub = nullptr;
    for (const CLI::App* s : app.get_subcommands()) sub = s;
    const std::string help = sub ? fmt::format("ccdlab {} --help", sub->get_name()) : "ccdlab --help";
    return user_error(fmt::format("{} ({})", e.what(), help));
  }
  try {
    if (*run_cmd) {
      run.progress = !no_progress;
      return run_command(run);
    }
    if (*step_cmd) {
      step.progress = !step_no_progress;
      return step_command(step);
    }
    if (*proximity_cmd) {
      proximity.progress = !proximity_no_progress;
      return proximity_command(proximity);
    }
    if (*simulate_cmd) {
      simulate.progress = !simulate_no_progress;
      return simulate_command(simulate);
    }
    if (*export_cmd) {
      export_opts.progress = !export_no_progress;
      return export_command(export_opts);
    }
    if (*sweep_cmd) {
      sweep.progress = !sweep_no_progress;
      return sweep_command(sweep);
    }
    if (*bench_cmd) {
      bench.progress = !bench_no_progress;
      return bench_command(bench);
    }
    if (*validate_cmd) {
      validate.progress = !validate_no_progress;
      return validate_command(validate);
    }
    if (*list_cmd) return list_command(settings_table);
    if (*info_cmd) return info_command();
  } catch (const ccdlab::Error& e) {
    return user_error(e.what());
  } catch (const std::bad_alloc&) {
    return user_error("out of memory: the run needs more memory than this machine could give (lower the scene's "
                      "size, or set memory_limit to be told before a run starts)");
  } catch (const std::exception& e) {
    fmt::print(stderr, "ccdlab: internal error: {}\nThis is a bug in ccdlab: please report it with the command line "
               "and the output of 'ccdlab info'.\n", e.what());
    return kInternalError;
  } catch (...) {
    fmt::print(stderr, "ccdlab: internal error: unknown exception\nThis is a bug in ccdlab: please report it with the "
               "command line and the output of 'ccdlab info'.\n");
    return kInternalError;
  }
  return 1;
}
