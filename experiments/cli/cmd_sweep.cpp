// `ccdlab sweep FILE.yaml [--set k=v …] [--shard i/n] [--dry-run] [--force] [--merge]`: runs every combination of
// the file's `sweep:` block (framework/config/sweep.hpp), each into its own folder, skipping complete ones, or
// merges the finished runs into one table, runs.csv in the sweep's output.dir.
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/report.hpp"
#include "framework/config/sweep.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/progress.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {
namespace {
namespace fs = std::filesystem;

bool complete(const SweepRun& run) { return fs::exists(fs::path(run.dir) / kRunDoneFile); }

/// Nested JSON → "a.b.c" columns (lists as JSON text).
void flatten(const nlohmann::json& j, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, out);
  } else if (j.is_string()) {
    out.emplace_back(prefix, j.get<std::string>());
  } else {
    out.emplace_back(prefix, j.dump());
  }
}

int merge(const SweepPlan& plan) {
  std::vector<std::string> columns;
  std::map<std::string, bool> known;
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<const SweepRun*> missing;
  for (const SweepRun& run : plan.runs) {
    if (!complete(run)) {
      missing.push_back(&run);
      continue;
    }
    const std::string path = (fs::path(run.dir) / kRunDoneFile).string();
    nlohmann::json j;
    try {
      std::ifstream in(path);
      j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      fail("{}: not a run record ({}); delete it, or rerun that run with --force", path, e.what());
    }
    std::vector<std::pair<std::string, std::string>> cells;
    // What a reader looks for first: which run, its result, where it ran; then every resolved config key.
    flatten(j.at("run"), "", cells);
    flatten(j.at("result"), "", cells);
    flatten(j.at("machine"), "", cells);
    flatten(j.at("config"), "", cells);
    std::map<std::string, std::string> row;
    for (auto& [k, v] : cells) {
      if (!known[k]) {
        known[k] = true;
        columns.push_back(k);
      }
      row[k] = v;
    }
    rows.push_back(std::move(row));
  }
  create_output_dir(plan.output_dir, "output.dir");
  const std::string out_path = (fs::path(plan.output_dir) / "runs.csv").string();
  OutputFile out(out_path, "output.dir");
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << csv_field(columns[c]);
  out << "\n";
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto it = row.find(columns[c]);
      out << (c ? "," : "") << (it == row.end() ? "" : csv_field(it->second));
    }
    out << "\n";
  }
  out.commit();
  fmt::print("merged {} of {} runs into {}\n", rows.size(), plan.runs.size(), out_path);
  for (std::size_t i = 0; i < missing.size() && i < 10; ++i)
    fmt::print(stderr, "ccdlab sweep: run {} not finished ({} rep {}): {}\n", missing[i]->index,
               missing[i]->label.empty() ? "base" : missing[i]->label, missing[i]->repeat, missing[i]->dir);
  if (missing.size() > 10) fmt::print(stderr, "ccdlab sweep: … and {} more not finished\n", missing.size() - 10);
  return 0;
}

}  // namespace

int sweep_command(const SweepOptions& o) {
  const auto [shard, shards] = parse_shard(o.shard);
  if (o.merge && (o.dry_run || o.force))
    fail("--merge gathers the finished runs and runs nothing: it does not combine with --dry-run or --force");
  const Registries reg = builtin_registries();
  const SweepPlan plan = plan_sweep(o.config, o.overrides, reg);
  if (o.merge) return merge(plan);

  std::vector<const SweepRun*> mine;
  for (const SweepRun& run : plan.runs)
    if (in_shard(run.index, shard, shards)) mine.push_back(&run);
  std::size_t already = 0;
  for (const SweepRun* run : mine) already += complete(*run);
  fmt::print("ccdlab sweep {}: {} combinations × {} repeat(s) = {} runs (varied: {}); shard {}/{} holds {}, {} complete\n",
             o.config, plan.combinations, plan.repeats, plan.runs.size(),
             plan.keys.empty() ? "nothing" : fmt::format("{}", fmt::join(plan.keys, ", ")), shard, shards, mine.size(),
             already);
  if (o.dry_run) {
    fmt::print("{:>5}  {:>3}  {:<8}  {}\n", "run", "rep", "status", "folder");
    for (const SweepRun* run : mine)
      fmt::print("{:>5}  {:>3}  {:<8}  {}\n", run->index, run->repeat,
                 complete(*run) ? (o.force ? "rerun" : "complete") : "to run", run->dir);
    return 0;
  }

  Progress progress("ccdlab sweep", long(mine.size()), o.progress);
  std::size_t ran = 0, skipped = 0;
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const SweepRun& run = *mine[i];
    const std::string name = run.label.empty() ? "base" : run.label;
    if (complete(run) && !o.force) {
      ++skipped;
      fmt::print("[{}/{}] run {} {} rep {}: complete, skipped\n", i + 1, mine.size(), run.index, name, run.repeat);
      progress.update(long(i + 1));
      continue;
    }
    create_output_dir(run.dir, "output.dir");
    const std::string done_path = (fs::path(run.dir) / kRunDoneFile).string();
    remove_stale_output(done_path, "output.dir");  // a rerun is incomplete until it is written again
    RunOptions ro;
    ro.quiet = true;
    ro.progress = false;
    const nlohmann::json summary = run_experiment(run.config, reg, ro);
    nlohmann::json result = summary;
    for (const char* k : {"config", "results", "git_revision", "experiment"}) result.erase(k);
    const nlohmann::json record = {
        {"run", {{"sweep", plan.source}, {"index", run.index}, {"repeat", run.repeat}, {"combination", run.combination},
                 {"label", name}, {"config_hash", run.config_hash}, {"dir", run.dir}}},
        {"config", summary.at("config")},
        {"result", result},
        {"machine", {{"git_revision", build_info::git_revision}, {"compiler", build_info::compiler},
                     {"build_type", build_info::build_type}, {"cpu", cpu_model()},
                     {"hardware_threads", std::thread::hardware_concurrency()}}}};
    OutputFile done(done_path, "output.dir");
    done << record.dump(2) << "\n";
    done.commit();
    ++ran;
    fmt::print("[{}/{}] run {} {} rep {}: {:.2f} ms/step, contacts vf={} ee={}, hash {}\n", i + 1, mine.size(),
               run.index, name, run.repeat, summary.at("ms_per_step").get<double>(),
               summary.at("contacts").at("vf").get<std::uint64_t>(), summary.at("contacts").at("ee").get<std::uint64_t>(),
               summary.at("hash").get<std::string>());
    progress.update(long(i + 1));
  }
  fmt::print("ran {}, skipped {} complete; gather them with: ccdlab sweep {} --merge\n", ran, skipped, o.config);
  return 0;
}

}  // namespace ccdlab::cli
