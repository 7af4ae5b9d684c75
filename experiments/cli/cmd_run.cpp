// `ccdlab run CONFIG.yaml [--set key=value …] [--json]`: runs an experiment step by step; prints a per-step
// table (or one JSON summary), writes steps.csv, steps.jsonl, config.yaml (and contacts.csv) to output.dir.
#include <filesystem>

#include <unistd.h>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/report.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/memory.hpp"
#include "experiments/cli/step_progress.hpp"
#include "framework/util/progress.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {
namespace {

/// What a run adds up over its steps, and the summary it reports at the end.
struct RunTotals {
  std::vector<double> total_ms, build_ms, cones_ms, swept_ms, refit_ms, traverse_ms, narrow_ms, orphan_ms;
  std::uint64_t hash = contact_set_hash({}), vf = 0, ee = 0, bv_tests = 0, candidates = 0, vf_tests = 0, ee_tests = 0,
                orphan_pairs = 0, orphan_tests = 0, tests_filtered = 0, tests_fallback = 0, peak_rss = 0,
                streamed_steps = 0, page_faults = 0;

  void add(const StepResult& r) {
    hash = contact_set_hash(r.contacts, hash);
    vf += r.counters.contacts_vf;
    ee += r.counters.contacts_ee;
    bv_tests += r.counters.bv_tests;
    candidates += r.counters.candidate_pairs;
    vf_tests += r.counters.vf_tests;
    ee_tests += r.counters.ee_tests;
    orphan_pairs += r.counters.orphan_vf + r.counters.orphan_ee;
    orphan_tests += r.counters.orphan_tests;
    tests_filtered += r.counters.tests_filtered;
    tests_fallback += r.counters.tests_fallback;
    peak_rss = std::max(peak_rss, r.memory.peak_rss_bytes);
    streamed_steps += r.memory.slices > 0;
    page_faults += r.memory.page_faults;
    total_ms.push_back(r.timings.total_ms);
    build_ms.push_back(r.timings.build_ms);
    cones_ms.push_back(r.timings.cones_ms);
    swept_ms.push_back(r.timings.swept_bv_ms);
    refit_ms.push_back(r.timings.refit_ms);
    traverse_ms.push_back(r.timings.traverse_ms);
    narrow_ms.push_back(r.timings.narrow_ms);
    orphan_ms.push_back(r.timings.orphan_ms);
  }

  [[nodiscard]] nlohmann::json summary(const ExperimentConfig& config, const MeshSequence& scene,
                                       const nlohmann::json& config_json) const {
    return {{"experiment", config.name},
            {"scene", scene.description()},
            {"triangles", scene.topology().num_faces()},
            {"steps", scene.num_steps()},
            {"ms_per_step", median(total_ms)},  // the median step; a 1-step run includes the BVH build
            {"ms_per_phase",
             {{"build_once", build_ms.front()},
              {"swept_bv", median(swept_ms)},
              {"refit", median(refit_ms)},
              {"normal_cones", median(cones_ms)},
              {"traverse", median(traverse_ms)},
              {"narrow", median(narrow_ms)},
              {"orphans", median(orphan_ms)}}},
            {"contacts", {{"vf", vf}, {"ee", ee}}},
            {"counters", {{"bv_tests", bv_tests}, {"candidate_pairs", candidates}, {"vf_tests", vf_tests},
                          {"ee_tests", ee_tests}, {"orphan_pairs", orphan_pairs}, {"orphan_tests", orphan_tests},
                          {"tests_filtered", tests_filtered}, {"tests_fallback", tests_fallback}}},
            {"hash", fmt::format("{:016x}", hash)},
            {"memory", {{"peak_rss_mb", double(peak_rss) / (1 << 20)}, {"limit_mb", double(config.memory_limit_bytes) / (1 << 20)},
                        {"streamed_steps", streamed_steps}, {"page_faults", page_faults}}},
            {"config", config_json},
            {"git_revision", build_info::git_revision},
            {"results", config.output.dir}};
  }

  /// The table's last lines: the medians, the contacts, the memory.
  void print_footer(const ExperimentConfig& config, int steps) const {
    const std::string cones = config.normal_cones ? fmt::format(", normal cones {:.2f}", median(cones_ms)) : "";
    fmt::print("\n{} steps: median {:.2f} ms/step (swept BV {:.2f}, refit {:.2f}{}, traverse {:.2f}, narrow {:.2f}, "
               "orphans {:.2f}); contacts vf={} ee={}; hash {:016x}\npeak resident memory {} (limit {}{})\nresults in {}/\n",
               steps, median(total_ms), median(swept_ms), median(refit_ms), cones, median(traverse_ms),
               median(narrow_ms), median(orphan_ms), vf, ee, hash, format_bytes(peak_rss),
               config.memory_limit_bytes ? format_bytes(config.memory_limit_bytes) : "none",
               streamed_steps ? fmt::format("; {} steps streamed to stay under it", streamed_steps) : "", config.output.dir);
  }
};

/// A run's result files (output.dir), written under temporary names and renamed when the run is complete; results
/// of an earlier run that this one replaces are removed first, so the folder never mixes the two or shows a
/// partial run.
class RunFiles {
 public:
  RunFiles(const ExperimentConfig& config, const MeshSequence& scene, const nlohmann::json& config_json)
      : dir_(config.output.dir),
        fixed_cols_(fmt::format("{},{},{},{},{},{},{}", config.name, config.scheduler.name, config.threads, config.k,
                                config.width, config.tester.name, build_info::git_revision)) {
    create_output_dir(dir_, "output.dir");
    for (const char* name : {"config.yaml", "steps.csv", "steps.jsonl", "contacts.csv"})
      remove_stale_output(path(name), "output.dir");
    yaml_ = open("config.yaml");
    yaml_ << "# resolved by ccdlab " << build_info::git_revision << " from " << config.source << "\n" << to_yaml(config_json);
    if (config.output.csv) {
      csv_ = open("steps.csv");
      csv_ << "step,frame_t0,frame_t1," << csv_header() << ",experiment,scheduler,threads,k,bv_width,tester,git_revision\n";
    }
    if (config.output.jsonl) {
      jsonl_ = open("steps.jsonl");
      jsonl_ << nlohmann::json{{"type", "config"}, {"config", config_json}, {"git_revision", build_info::git_revision},
                               {"scene", scene.description()}, {"triangles", scene.topology().num_faces()},
                               {"vertices", scene.topology().num_vertices()}}
                    .dump()
             << "\n";
    }
    if (config.output.contacts) {
      contacts_ = open("contacts.csv");
      contacts_ << "step," << kContactColumns << "\n";
    }
  }

  /// Step s (frames f0 → f1 at positions x_t0 → x_t1): its row, record and contacts.
  void write_step(int s, const std::string& f0, const std::string& f1, const StepResult& r, const Positions& x_t0,
                  const Positions& x_t1) {
    const std::uint64_t step_hash = contact_set_hash(r.contacts);
    if (csv_.is_open()) csv_ << fmt::format("{},{},{},{},{}\n", s, f0, f1, csv_row(r, step_hash), fixed_cols_);
    if (jsonl_.is_open()) {
      nlohmann::json j = step_json(r);
      j["type"] = "step";
      j["step"] = s;
      j["frame_t0"] = f0;
      j["frame_t1"] = f1;
      j["hash"] = fmt::format("{:016x}", step_hash);
      jsonl_ << j.dump() << "\n";
    }
    if (contacts_.is_open())
      for (const Contact& c : r.contacts) contacts_ << s << "," << contact_row(c, x_t0, x_t1) << "\n";
  }

  /// The summary record, then every file renamed to its name.
  void finish(const nlohmann::json& summary) {
    if (jsonl_.is_open()) {
      nlohmann::json j = summary;
      j["type"] = "summary";
      jsonl_ << j.dump() << "\n";
    }
    for (OutputFile* f : {&yaml_, &csv_, &jsonl_, &contacts_}) f->commit();
  }

 private:
  std::string path(const char* name) const { return (std::filesystem::path(dir_) / name).string(); }
  OutputFile open(const char* name) const { return OutputFile(path(name), "output.dir"); }

  std::string dir_, fixed_cols_;
  OutputFile yaml_, csv_, jsonl_, contacts_;
};

}  // namespace

int run_command(const RunOptions& o) {
  const Registries reg = builtin_registries();
  const ExperimentConfig config = load_experiment(o.config, o.overrides, reg);
  const nlohmann::json summary = run_experiment(config, reg, o);
  if (o.json) fmt::print("{}\n", summary.dump(2));
  return 0;
}

nlohmann::json run_experiment(const ExperimentConfig& config, const Registries& reg, const RunOptions& o) {
  const nlohmann::json config_json = to_json(config);
  const MeshSequence scene = make_scene(config, reg);
  CcdPipeline pipeline(scene.topology(), scene.bodies(), make_strategies(config, reg));
  RunFiles files(config, scene, config_json);

  const bool table = !o.json && !o.quiet;
  if (table) {
    fmt::print("ccdlab run {} — {}\n", config.name, scene.description());
    fmt::print("  k={} width={} hierarchy={} scheduler={} threads={} tester={}  ({} triangles, {} orphan VF + {} orphan EE, rev {})\n\n",
               config.k, config.width, config.hierarchy.name, config.scheduler.name, config.threads, config.tester.name,
               scene.topology().num_faces(), pipeline.orphans().vf.size(), pipeline.orphans().ee.size(),
               build_info::git_revision);
    print_table_header(stdout);
  }
  // When the table rows go to the same terminal they are the progress; otherwise show a progress line.
  const bool table_on_terminal = table && isatty(STDOUT_FILENO);
  Progress progress("ccdlab run", scene.num_steps(), o.progress && !table_on_terminal);
  StepProgressLine step_line(pipeline, o.progress);  // inside a step that runs longer than two seconds
  RunTotals totals;
  Positions x_t0 = scene.frame(0);
  StepResult r;  // one for every step: its contact list's memory reused
  for (int s = 0; s < scene.num_steps(); ++s) {
    Positions x_t1 = scene.frame(s + 1);
    pipeline.step(x_t0, x_t1, r);
    step_line.clear();
    totals.add(r);
    const std::string &f0 = scene.frame_label(s), &f1 = scene.frame_label(s + 1);
    if (table) print_table_row(stdout, fmt::format("{}>{}", f0, f1), r);
    files.write_step(s, f0, f1, r, x_t0, x_t1);
    x_t0 = std::move(x_t1);
    progress.update(s + 1);
  }
  const nlohmann::json summary = totals.summary(config, scene, config_json);
  files.finish(summary);
  if (table) totals.print_footer(config, scene.num_steps());
  return summary;
}

}  // namespace ccdlab::cli
