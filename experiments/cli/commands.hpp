#pragma once
// The ccdlab subcommands. Each returns the process exit code; user errors are thrown as ccdlab::Error and
// turned into a message on stderr and exit code 2 by main.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "framework/config/experiment.hpp"
#include "framework/config/pipeline_config.hpp"
#include "framework/hierarchy/wide_bvh.hpp"

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
  std::string out;                     ///< folder for the VTK files
  bool progress = true;
};
int export_command(const ExportOptions& o);

/// The pipeline's settings as flags (`step`, `proximity`), their defaults those of PipelineSettings
/// (pipeline_settings.hpp).
struct PipelineFlags {
  int k = PipelineSettings{}.k;
  int width = PipelineSettings{}.width;
  std::string end_boxes{to_string(PipelineSettings{}.end_boxes)};  ///< bv.end_boxes (kEndBoxModes)
  std::string scheduler = kDefaultScheduler;
  std::string hierarchy = kDefaultHierarchy;
  std::string tester = kDefaultTester;
  std::string narrow{to_string(NarrowOptions{}.mode)};
  std::string representative{to_string(NarrowOptions{}.representative)};
  int threads = PipelineSettings{}.threads;
  std::string memory_limit = kDefaultMemoryLimit;
  double candidate_limit = kDefaultCandidateLimit;
  double time_limit = 0;
};
/// The flags as a pipeline's configuration, each checked as a YAML key is, spelled as its flag in messages.
PipelineConfig pipeline_config(const PipelineFlags& f);
/// How the CLI spells a setting in messages: its flag (bv.width → --bv-width).
std::string flag_of(std::string_view key);

struct StepOptions : PipelineFlags {
  std::string mesh_t0, mesh_t1;
  bool progress = true;  ///< a progress line on stderr while a long step runs (when stderr is a terminal)
  std::string contacts_csv;
  bool json = false;
  bool earliest = false;  ///< only the earliest time of contact (CcdPipeline::earliest_toi)
};
int step_command(const StepOptions& o);

/// `ccdlab proximity`: the pairs closer than dhat in one mesh file (framework/pipeline/proximity_query.hpp); the
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
  std::vector<std::string> testers = {"float", "filtered", "conservative", "exact"};
  int repeat = 3;                  ///< time each query this many times, keep the fastest
  std::string out_dir;             ///< write validate.csv / validate.jsonl here
  int failures = 0;                ///< list up to this many wrong answers per tester and set
  bool check = false;              ///< exit 1 when exact disagrees with the truth or conservative misses
  bool json = false;
  bool progress = true;
};
int validate_command(const ValidateOptions& o);

int list_command();
int info_command();

}  // namespace ccdlab::cli
