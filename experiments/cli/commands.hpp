#pragma once
// The ccdlab subcommands. Each returns the process exit code; user errors are thrown as ccdlab::Error and
// turned into a message on stderr and exit code 2 by main.
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "framework/config/experiment.hpp"
#include "framework/config/pipeline_config.hpp"
#include "framework/config/settings.hpp"
#include "framework/hierarchy/wide_bvh.hpp"

namespace CLI {
class Option;
}  // namespace CLI

namespace ccdlab::cli {

struct RunOptions {
  std::string config;
  std::vector<std::string> overrides;  ///< --set key=value
  bool json = false;
  bool quiet = false;  ///< neither the table nor the summary on stdout (a sweep's runs)
  bool progress = true;
};
int run_command(const RunOptions& o);
/// Runs one resolved experiment: writes its result files to output.dir, prints its table unless json/quiet;
/// returns the summary (also the last line of steps.jsonl).
nlohmann::json run_experiment(const ExperimentConfig& config, const Registries& reg, const RunOptions& o);

struct SweepOptions {
  std::string config;
  std::vector<std::string> overrides;  ///< --set key=value, applied to every run
  std::string shard = "0/1";
  bool dry_run = false;
  bool force = false;
  bool merge = false;
  bool progress = true;
};
int sweep_command(const SweepOptions& o);

struct SimulateOptions {
  std::string scene;                   ///< experiments/scenes/<name>.yaml
  std::vector<std::string> overrides;  ///< --set key=value (frames=8, resolution=0.1, threads=2 …)
  std::string out;                     ///< default results/scenes/<name>-<scene hash>
  bool force = false;                  ///< simulate even when the folder holds this scene's frames
  bool progress = true;
};
int simulate_command(const SimulateOptions& o);

struct ExportOptions {
  std::string config;
  std::vector<std::string> overrides;  ///< --set key=value
  int step = -1;                       ///< the step drawn in detail; −1 = the one with the most contacts
  int levels = 8;                      ///< BVH depths drawn: 0 … levels − 1
  std::string out;                     ///< folder for the VTK files (or none, with html)
  std::string html;                    ///< the teaching page (one self-contained .html), or none
  bool progress = true;
};
int export_command(const ExportOptions& o);

/// The pipeline's settings as a command's flags (`step`, `proximity`): one per row of the settings table
/// (framework/config/settings.def), added by main.cpp's add_setting_flags; what the command line gave is read
/// by pipeline_config, each value checked as a YAML key's is and spelled as its flag in messages.
struct PipelineFlags {
  std::deque<std::string> texts;  ///< each flag's text as CLI11 writes it (a deque: the addresses stay)
  std::vector<std::pair<const Setting*, const CLI::Option*>> options;  ///< texts[i]'s row and its flag
};
/// The configuration the flags give: the defaults, each given flag set through its row.
PipelineConfig pipeline_config(const PipelineFlags& f);
/// How the CLI spells a setting in messages: its flag (bv.width → --bv-width).
SettingName flag_of();

struct StepOptions : PipelineFlags {
  std::string mesh_t0, mesh_t1;
  bool progress = true;  ///< a progress line on stderr while a long step runs (when stderr is a terminal)
  std::string contacts_csv;
  bool json = false;
  bool earliest = false;  ///< only the earliest time of contact (CcdPipeline::earliest_toi)
};
int step_command(const StepOptions& o);

/// `ccdlab proximity`: the pairs closer than dhat in one mesh file (framework/pipeline/proximity/proximity_query.hpp); the
/// pipeline's flags less --tester.
struct ProximityOptions : PipelineFlags {
  std::string mesh;
  double dhat = 0;
  bool relative = false;  ///< dhat is a fraction of the mesh's bounding-box diagonal
  int repeat = 1;         ///< queries on the same positions: the first builds the hierarchy, the others refit it
  bool check = false;     ///< also run the reference (sweep_proximity), time it, exit 1 unless the pairs are equal
  bool progress = true;
  std::string pairs_csv;
  bool json = false;
};
int proximity_command(const ProximityOptions& o);

struct BenchOptions {
  std::string config;
  std::vector<std::string> overrides;
  std::string schedulers = "sequential,phc,front,static";
  std::string threads = "1,2";
  std::string narrow{to_string(NarrowOptions{}.mode)};  ///< narrow modes, e.g. "batched,scalar" to measure their ratio side by side
  std::string cores = "1,2,4,8,16,32,64";
  int rounds = 3;
  int untimed_steps = 0;  ///< the first K steps of every run are run and checked, not timed (a steady state)
  bool json = false;
  bool progress = true;
};
int bench_command(const BenchOptions& o);

struct ValidateOptions {
  std::vector<std::string> paths;  ///< query CSV files / folders, or "hard-cases"
  std::vector<std::string> testers;  ///< specs; none: every registered tester at its defaults (the ladder)
  int repeat = 3;                  ///< time each query this many times, keep the fastest
  std::string out_dir;             ///< write validate.csv / validate.jsonl here
  int failures = 0;                ///< list up to this many wrong answers per tester and set
  bool check = false;              ///< exit 1 when exact disagrees with the truth or a tester that never misses does
  bool json = false;
  bool progress = true;
};
int validate_command(const ValidateOptions& o);

/// The registries and their parameters; with `settings_table`, docs/config.md's table of settings (Markdown).
int list_command(bool settings_table = false);
int info_command();

}  // namespace ccdlab::cli
