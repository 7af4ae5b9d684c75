// ccdlab: command-line entry point. Subcommands: run, sweep, step, proximity, bench, simulate, export, validate, list, info
// (see README.md and docs/cli.md): one function each below adds its flags and says how it runs; main parses the
// command line and runs the one given, turning every failure into its exit code.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <new>
#include <string_view>
#include <vector>

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


using namespace ccdlab::cli;

/// A subcommand: its flags, bound to options it owns, and how it runs once they are parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

/// `--no-progress`: clears `progress` (a progress line on stderr is shown only where stderr is a terminal anyway).
template <class Options>
void add_progress_flag(CLI::App* cmd, Options& o, const char* doc = "no progress line on stderr") {
  cmd->add_flag_callback("--no-progress", [&o] { o.progress = false; }, doc);
}

/// Options that live as long as the program (CLI11 writes into them while parsing).
template <class Options>
Options& owned() {
  static Options options;
  return options;
}

Command add_run(CLI::App& app) {
  auto& o = owned<RunOptions>();
  auto* cmd = app.add_subcommand("run", "run a YAML experiment: per-step table, CSV/JSONL results");
  cmd->add_option("config", o.config, "experiment YAML file")->required();
  cmd->add_option("--set", o.overrides, "override a config key, e.g. --set bv.k=26 (repeatable)");
  cmd->add_flag("--json", o.json, "print one JSON summary instead of the table");
  add_progress_flag(cmd, o);
  return {cmd, [&o] { return run_command(o); }};
}

Command add_sweep(CLI::App& app) {
  auto& o = owned<SweepOptions>();
  auto* cmd = app.add_subcommand("sweep", "run every combination of a YAML sweep (resumable, shardable), or "
                                          "merge the finished runs into runs.csv");
  cmd->add_option("config", o.config, "experiment YAML file with a sweep: block")->required();
  cmd->add_option("--set", o.overrides, "override a config key in every run (repeatable)");
  cmd->add_option("--shard", o.shard, "run only shard i of n (runs whose index mod n = i), e.g. 0/4")->capture_default_str();
  cmd->add_flag("--dry-run", o.dry_run, "list the runs (index, shard, done or not, folder) and run nothing");
  cmd->add_flag("--force", o.force, "run again the runs whose folder already holds a complete result");
  cmd->add_flag("--merge", o.merge, "gather every finished run into runs.csv in output.dir; run nothing");
  add_progress_flag(cmd, o);
  return {cmd, [&o] { return sweep_command(o); }};
}

Command add_step(CLI::App& app) {
  auto& o = owned<StepOptions>();
  auto* cmd = app.add_subcommand("step", "one CCD step between two mesh files (PLY or OBJ)");
  cmd->add_option("t0", o.mesh_t0, "mesh at the start of the step")->required();
  cmd->add_option("t1", o.mesh_t1, "mesh at the end of the step (same topology)")->required();
  add_setting_flags(cmd, o);
  add_progress_flag(cmd, o, "no progress line on stderr while a long step runs");
  cmd->add_option("--contacts", o.contacts_csv, "write contacts to this CSV (kind,a,b,c,d,toi,u,v,nx,ny,nz)");
  cmd->add_flag("--json", o.json, "print JSON instead of the table");
  cmd->add_flag("--earliest", o.earliest, "only the earliest time of contact (1 when none; JSON: earliest_toi), "
                "skipping the pairs that cannot beat the best time found");
  return {cmd, [&o] { return step_command(o); }};
}

Command add_proximity(CLI::App& app) {
  auto& o = owned<ProximityOptions>();
  auto* cmd = app.add_subcommand("proximity", "every vertex-face and edge-edge pair closer than --dhat in one "
                                              "mesh file: distance and closest-feature type (a barrier solver's active set)");
  cmd->add_option("mesh", o.mesh, "mesh file (PLY or OBJ)")->required();
  cmd->add_option("--dhat", o.dhat, "the distance: pairs closer than it are reported")->required();
  cmd->add_flag("--relative", o.relative, "--dhat is a fraction of the mesh's bounding-box diagonal");
  add_setting_flags(cmd, o, {"tester", "normal_cones"});
  cmd->add_option("--repeat", o.repeat, "queries on the same positions (the first builds the hierarchy, "
                  "the others refit it): ms of the first and median of the others")->capture_default_str();
  cmd->add_flag("--check", o.check, "also find the pairs without the hierarchy (a sweep over boxes, the "
                "same exact test: the reference and baseline), time it, exit 1 unless both find the same pairs");
  add_progress_flag(cmd, o, "no progress line on stderr while a long query runs");
  cmd->add_option("--pairs", o.pairs_csv, "write the pairs to this CSV (kind,a,b,c,d,distance,type,u,v)");
  cmd->add_flag("--json", o.json, "print JSON instead of the summary");
  return {cmd, [&o] { return proximity_command(o); }};
}

Command add_bench(CLI::App& app) {
  auto& o = owned<BenchOptions>();
  auto* cmd = app.add_subcommand("bench", "schedulers x threads in alternating rounds; counters; simulated scaling");
  cmd->add_option("config", o.config, "experiment YAML file (scene, k, tester, output.dir)")->required();
  cmd->add_option("--set", o.overrides, "override a config key (repeatable)");
  cmd->add_option("--schedulers", o.schedulers, "comma-separated schedulers")->capture_default_str();
  cmd->add_option("--narrow", o.narrow, "comma-separated narrow modes: batched, scalar (side by side)")->capture_default_str();
  cmd->add_option("--threads", o.threads, "comma-separated thread counts")->capture_default_str();
  cmd->add_option("--cores", o.cores, "simulated core counts")->capture_default_str();
  cmd->add_option("--rounds", o.rounds, "alternating rounds")->capture_default_str();
  cmd->add_option("--untimed-steps", o.untimed_steps,
                  "run and check the first K steps of every run without timing them (a steady state)")->capture_default_str();
  cmd->add_flag("--json", o.json, "print one JSON object instead of the tables");
  add_progress_flag(cmd, o);
  return {cmd, [&o] { return bench_command(o); }};
}

Command add_simulate(CLI::App& app) {
  auto& o = owned<SimulateOptions>();
  auto* cmd = app.add_subcommand("simulate", "simulate a scene with only the effects it lists; frames as PLY + meta.json");
  cmd->add_option("scene", o.scene, "scene YAML file (experiments/scenes/)")->required();
  cmd->add_option("--set", o.overrides, "override a scene key: frames=8, resolution=0.1, threads=2 (repeatable)");
  cmd->add_option("--out", o.out, "folder for the frames (default: results/scenes/NAME-HASH)");
  cmd->add_flag("--force", o.force, "simulate even when the folder holds this scene's frames");
  add_progress_flag(cmd, o);
  return {cmd, [&o] { return simulate_command(o); }};
}

Command add_export(CLI::App& app) {
  auto& o = owned<ExportOptions>();
  auto* cmd = app.add_subcommand("export", "VTK files for ParaView / meshio: mesh per frame with contact counts, "
                                           "BVH levels as k-DOP polyhedra, the BVTT front, the contacts");
  cmd->add_option("config", o.config, "experiment YAML file")->required();
  cmd->add_option("--set", o.overrides, "override a config key (repeatable)");
  cmd->add_option("--step", o.step, "the step drawn in detail (default: the one with the most contacts)");
  cmd->add_option("--levels", o.levels, "BVH depths to draw, from the root")->capture_default_str();
  cmd->add_option("--out", o.out, "folder for the .vtu / .pvd files");
  cmd->add_option("--html", o.html, "one self-contained page to open in a browser: the steps, BVH levels, front, "
                                    "contacts at every K, and a walk-through of the BVTT per scheduler");
  add_progress_flag(cmd, o);
  return {cmd, [&o] { return export_command(o); }};
}

Command add_validate(CLI::App& app) {
  auto& o = owned<ValidateOptions>();
  auto* cmd = app.add_subcommand("validate", "testers against elementary query sets with known answers");
  cmd->add_option("paths", o.paths, "query CSV files or folders (../shared/data/ccd-queries), or hard-cases")->required();
  cmd->add_option("--tester", o.testers, "tester, e.g. float or conservative:delta=1e-4,fallback=exact (repeatable; "
                                         "default: every tester of the ladder, `ccdlab list`)");
  cmd->add_option("--repeat", o.repeat, "time each query this many times, keep the fastest")->capture_default_str();
  cmd->add_option("--out", o.out_dir, "write validate.csv, validate.jsonl and queries.csv (per query) into this folder");
  cmd->add_option("--failures", o.failures, "list up to N wrong answers per tester and set");
  cmd->add_flag("--check", o.check, "exit 1 if exact disagrees with the truth, or conservative or inclusion misses");
  cmd->add_flag("--json", o.json, "print JSON instead of the table");
  add_progress_flag(cmd, o);
  return {cmd, [&o] { return validate_command(o); }};
}

Command add_list(CLI::App& app) {
  static bool settings_table = false;
  auto* cmd = app.add_subcommand("list", "the settings, and the registered strategies and their parameters");
  cmd->add_flag("--settings", settings_table, "print the settings table (docs/config.md's) as Markdown");
  return {cmd, [] { return list_command(settings_table); }};
}

Command add_info(CLI::App& app) {
  return {app.add_subcommand("info", "compiler, flags, OpenMP, git revision"), [] { return info_command(); }};
}

/// Runs a parsed command: a user error (ccdlab::Error, out of memory) is one "ccdlab: error:" line and exit 2; any
/// other exception is a bug, exit 3.
int run_guarded(const Command& command) {
  try {
    return command.run();
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
}

}  // namespace

int main(int argc, char** argv) {
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
  const std::vector<Command> commands{add_run(app),      add_sweep(app),  add_step(app),     add_proximity(app),
                                      add_bench(app),    add_simulate(app), add_export(app), add_validate(app),
                                      add_list(app),     add_info(app)};

  // An unknown command is named (CLI11 would only say that a subcommand is required).
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const Command& c : commands) names.push_back(c.app->get_name());
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
  for (const Command& c : commands)
    if (*c.app) return run_guarded(c);
  return 1;
}
