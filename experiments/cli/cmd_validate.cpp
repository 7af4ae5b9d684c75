// `ccdlab validate PATH… [--tester NAME[:key=value,…]]…`: runs testers over elementary query sets with known
// answers (the shared CSV format, or `hard-cases` for the built-in degenerate families) and prints, per tester
// and set: false negatives and positives, µs per query (mean / median / p99 / max), how many a filter or a
// fallback decided, and the time-of-contact error against the exact tester.
#include <filesystem>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/report.hpp"
#include "framework/config/strategy_spec.hpp"
#include "framework/queries/evaluate.hpp"
#include "framework/queries/hard_cases.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/progress.hpp"
#include "strategies/registry.hpp"
#include "strategies/testers/exact_tester.hpp"

namespace ccdlab::cli {
namespace fs = std::filesystem;
namespace {

std::string label(const StrategyChoice& c, const TesterRegistry& registry) {
  std::string out = c.name;
  const auto defaults = registry.find(c.name)->defaults().all();
  for (const auto& [key, v] : c.params.all()) {
    if (defaults.at(key) == v) continue;
    const std::string& k = key;  // a structured binding cannot be captured by clang 14
    std::visit([&](const auto& x) { out += fmt::format("{}{}={}", out == c.name ? ":" : ",", k, x); }, v);
  }
  return out;
}

nlohmann::json score_json(const SetScore& s) {
  return {{"set", s.set}, {"scene", s.scene}, {"collection", s.collection}, {"tester", s.tester}, {"queries", s.queries}, {"positives", s.positives},
          {"false_negatives", s.false_negatives}, {"false_positives", s.false_positives}, {"filtered", s.filtered},
          {"fallbacks", s.fallbacks}, {"mean_us", s.mean_us}, {"median_us", s.median_us}, {"p99_us", s.p99_us},
          {"max_us", s.max_us}, {"toi_max_error", s.toi_max_error}, {"toi_mean_error", s.toi_mean_error},
          {"toi_late", s.toi_late}};
}

/// The testers of --tester, made from the registry, and their labels (a spec with only the parameters it changes).
std::pair<std::vector<std::unique_ptr<PrimitiveTester>>, std::vector<std::string>> make_testers(const ValidateOptions& o,
                                                                                                const Registries& reg) {
  std::vector<std::unique_ptr<PrimitiveTester>> testers;
  std::vector<std::string> names;
  for (const auto& spec : o.testers.empty() ? reg.testers.names() : o.testers) {
    const StrategyChoice c = parse_strategy_spec(spec, "--tester ", "tester", reg.testers, "float");
    testers.push_back(reg.testers.make(c));
    names.push_back(label(c, reg.testers));
  }
  return {std::move(testers), std::move(names)};
}

std::vector<QuerySet> load_sets(const std::vector<std::string>& paths) {
  std::vector<QuerySet> sets;
  for (const auto& path : paths) {
    auto more = path == "hard-cases" ? hard_case_sets() : load_query_sets(path);
    for (auto& s : more) sets.push_back(std::move(s));
  }
  return sets;
}

/// Every tester on every set, against the exact reference; each query's outcome written to `per_query` when open.
std::vector<SetScore> score_sets(const std::vector<QuerySet>& sets, const std::vector<std::unique_ptr<PrimitiveTester>>& testers,
                                 const std::vector<std::string>& names, int repeat, bool show_progress, OutputFile& per_query) {
  std::vector<SetScore> scores;
  std::size_t total = 0;
  for (const auto& s : sets) total += s.size();
  Progress progress("validate", long(total * (testers.size() + 1)), show_progress);
  long done = 0;
  for (const QuerySet& set : sets) {
    const std::vector<ToiReference> reference = exact_reference(set);
    progress.update(done += long(set.size()));
    for (std::size_t t = 0; t < testers.size(); ++t) {
      const auto outcomes = run_tester(*testers[t], set, repeat);
      scores.push_back(score(set, names[t], outcomes, reference));
      if (per_query.is_open())
        for (std::size_t i = 0; i < outcomes.size(); ++i)
          per_query << fmt::format("{},{},{},{},{},{},{},{},{},{:.4f},{:.17g},{:.17g}\n", set.name, set.scene,
                                   set.collection, names[t], i, csv_field(set.origin[i]), int(set.truth[i]),
                                   int(outcomes[i].hit), int(outcomes[i].route), outcomes[i].us, outcomes[i].toi,
                                   reference[i].hit ? reference[i].toi_lo : 1.0);
      progress.update(done += long(set.size()));
    }
  }
  return scores;
}

/// --check: 1 where exact disagrees with the truth, or a tester that never misses (conservative, inclusion)
/// missed a collision or reported a late time.
int check_status(const std::vector<SetScore>& scores) {
  for (const SetScore& s : scores) {
    const std::string tester_name = s.tester.substr(0, s.tester.find(':'));
    if (tester_name == "exact" && (s.false_negatives || s.false_positives)) return 1;
    if ((tester_name == "conservative" || tester_name == "inclusion") && (s.false_negatives || s.toi_late)) return 1;
  }
  return 0;
}

/// validate.csv and validate.jsonl in --out.
void write_scores(const ValidateOptions& o, const std::vector<std::string>& names, const std::vector<SetScore>& scores) {
  OutputFile csv((fs::path(o.out_dir) / "validate.csv").string(), "--out"),
      jsonl((fs::path(o.out_dir) / "validate.jsonl").string(), "--out");
  csv << "set,scene,collection,tester,queries,positives,false_negatives,false_positives,filtered,fallbacks,mean_us,"
         "median_us,p99_us,max_us,toi_max_error,toi_mean_error,toi_late,git_revision\n";
  for (const SetScore& s : scores)
    csv << fmt::format("{},{},{},{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.3g},{:.3g},{},{}\n", s.set, s.scene,
                       s.collection, s.tester, s.queries, s.positives, s.false_negatives, s.false_positives, s.filtered,
                       s.fallbacks, s.mean_us, s.median_us, s.p99_us, s.max_us, s.toi_max_error, s.toi_mean_error,
                       s.toi_late, build_info::git_revision);
  jsonl << nlohmann::json{{"type", "config"}, {"paths", o.paths}, {"testers", names}, {"repeat", o.repeat},
                          {"git_revision", build_info::git_revision}}.dump()
        << "\n";
  for (const SetScore& s : scores) {
    auto j = score_json(s);
    j["type"] = "score";
    jsonl << j.dump() << "\n";
  }
  csv.commit();
  jsonl.commit();
}

/// The table: a row per tester and set, then the totals per scene and tester, then what the columns mean.
void print_scores(const std::vector<SetScore>& scores) {
  std::size_t set_w = 3, tester_w = 6;
  for (const SetScore& s : scores) set_w = std::max(set_w, s.set.size()), tester_w = std::max(tester_w, s.tester.size());
  fmt::print("{:<{}}  {:<{}} {:>7} {:>6} {:>5} {:>5} {:>7} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "set", set_w, "tester",
             tester_w, "queries", "hits", "FN", "FP", "filter", "fallbk", "mean µs", "median µs", "p99 µs", "max µs",
             "ToI err");
  for (const SetScore& s : scores)
    fmt::print("{:<{}}  {:<{}} {:>7} {:>6} {:>5} {:>5} {:>7} {:>7} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.1f} {:>9.2g}\n", s.set,
               set_w, s.tester, tester_w, s.queries, s.positives, s.false_negatives, s.false_positives, s.filtered,
               s.fallbacks, s.mean_us, s.median_us, s.p99_us, s.max_us, s.toi_max_error);
  // Totals per scene and tester (µs: the mean over all the scene's queries).
  struct Total {
    std::size_t queries = 0, hits = 0, fn = 0, fp = 0, filtered = 0, fallbacks = 0;
    double us = 0;
  };
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, Total> totals;
  for (const SetScore& s : scores) {
    const auto key = std::pair{s.scene, s.tester};
    auto [it, fresh] = totals.try_emplace(key);
    if (fresh) order.push_back(key);
    Total& t = it->second;
    t.queries += s.queries, t.hits += s.positives, t.fn += s.false_negatives, t.fp += s.false_positives;
    t.filtered += s.filtered, t.fallbacks += s.fallbacks, t.us += s.mean_us * double(s.queries);
  }
  fmt::print("\ntotals per scene\n");
  for (const auto& key : order) {
    const Total& t = totals.at(key);
    fmt::print("{:<{}}  {:<{}} {:>7} {:>6} {:>5} {:>5} {:>7} {:>7} {:>9.3f}\n", key.first + "/*", set_w, key.second,
               tester_w, t.queries, t.hits, t.fn, t.fp, t.filtered, t.fallbacks, t.queries ? t.us / double(t.queries) : 0.0);
  }
  fmt::print("\nset: scene/kind (vertex-face, edge-edge, or the step's file stem); hits: queries whose ground truth is a "
             "collision;\nFN: collisions the tester missed; FP: non-colliding queries it reported; filter / fallbk: "
             "queries decided by\nits certified filter / by its fallback; µs per query (each timed --repeat times); ToI "
             "err: largest |toi − exact toi|\nover the queries both call a hit. --out writes validate.csv and "
             "queries.csv (one row per query, with its file:line).\n");
}

/// --failures: up to `n` wrong answers per tester and set, with the query's file and line.
void print_failures(const std::vector<SetScore>& scores, const std::vector<QuerySet>& sets, int n) {
  for (const SetScore& s : scores) {
    if (s.failures.empty()) continue;
    const QuerySet* set = nullptr;
    for (const auto& q : sets)
      if (q.name == s.set) set = &q;
    fmt::print("\n{} on {}: {} wrong\n", s.tester, s.set, s.failures.size());
    for (std::size_t k = 0; k < s.failures.size() && int(k) < n; ++k) {
      const std::size_t i = s.failures[k];
      fmt::print("  {} {}\n", set->truth[i] ? "missed   " : "false hit", set->origin[i]);
    }
  }
}

}  // namespace

int validate_command(const ValidateOptions& o) {
  if (o.repeat < 1 || o.repeat > 1000000) fail("--repeat: expected an integer from 1 to 1000000, got {}", o.repeat);
  if (o.failures < 0) fail("--failures: expected an integer >= 0, got {}", o.failures);
  const auto [testers, names] = make_testers(o, builtin_registries());
  const std::vector<QuerySet> sets = load_sets(o.paths);
  // Per-query outcomes (for plots of the time distribution), written as they come when --out is given.
  OutputFile per_query;
  if (!o.out_dir.empty()) {
    create_output_dir(o.out_dir, "--out");
    per_query = OutputFile((fs::path(o.out_dir) / "queries.csv").string(), "--out");
    per_query << "set,scene,collection,tester,query,origin,truth,hit,route,us,toi,exact_toi\n";
  }
  const std::vector<SetScore> scores = score_sets(sets, testers, names, o.repeat, o.progress, per_query);
  const int status = o.check ? check_status(scores) : 0;
  if (!o.out_dir.empty()) {
    write_scores(o, names, scores);
    per_query.commit();
  }
  if (o.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const SetScore& s : scores) j.push_back(score_json(s));
    fmt::print("{}\n", nlohmann::json{{"scores", j}, {"git_revision", build_info::git_revision}}.dump(2));
    return status;
  }
  print_scores(scores);
  if (o.failures > 0) print_failures(scores, sets, o.failures);
  if (status)
    fmt::print(stderr, "ccdlab validate: check failed (exact disagrees with the ground truth, or conservative or "
               "inclusion missed a "
               "collision or reported a late time of contact)\n");
  return status;
}

}  // namespace ccdlab::cli
