#include "framework/config/sweep.hpp"

#include <filesystem>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "framework/config/yaml_reader.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

/// One axis of the product: one key, or a zip group of keys whose values go together.
struct Axis {
  std::vector<std::string> keys;
  std::vector<std::vector<YAML::Node>> values;  ///< values[key][i]
  std::size_t size() const { return values.front().size(); }
};

std::string where(const std::string& path, const YAML::Node& n) { return fmt::format("{}:{}", path, n.Mark().line + 1); }

/// A YAML value as the text of a --set override (flow style, so maps and lists survive).
std::string as_override_text(const YAML::Node& v) {
  if (v.IsScalar()) return v.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << v;
  return out.c_str();
}

std::vector<YAML::Node> values_of(const std::string& path, const std::string& key, const YAML::Node& v) {
  std::vector<YAML::Node> out;
  if (v.IsSequence()) {
    for (const auto& x : v) out.push_back(x);
    if (out.empty()) fail("{}: sweep.{}: expected a non-empty list of values", where(path, v), key);
  } else if (v.IsDefined() && !v.IsNull()) {
    out.push_back(v);
  } else {
    fail("{}: sweep.{}: expected a value or a list of values", where(path, v), key);
  }
  return out;
}

/// The part of a run's folder name that says what it varies: key=value pairs, file-system safe.
std::string folder_label(const std::string& label) {
  std::string out;
  for (char ch : label) {
    const bool safe = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
                      ch == '.' || ch == '=' || ch == '-' || ch == '_';
    out += ch == ',' ? '_' : safe ? ch : '-';
  }
  if (out.size() > 120) out.resize(120);  // the hash after it keeps folders apart
  return out.empty() ? "base" : out;
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace

std::pair<std::size_t, std::size_t> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  std::size_t i = 0, n = 0;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used = 0;
    const std::string a = text.substr(0, slash), b = text.substr(slash + 1);
    if (a.empty() || b.empty() || a[0] == '-' || b[0] == '-') throw std::invalid_argument("sign");
    i = std::stoul(a, &used);
    if (used != a.size()) throw std::invalid_argument("trailing");
    n = std::stoul(b, &used);
    if (used != b.size()) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    fail("--shard: expected i/n with 0 <= i < n (e.g. 0/4), got '{}'", text);
  }
  if (n == 0 || i >= n) fail("--shard: expected i/n with 0 <= i < n (e.g. 0/4), got '{}'", text);
  return {i, n};
}

SweepPlan plan_sweep(const std::string& path, const std::vector<std::string>& overrides, const Registries& registries) {
  const YAML::Node root = load_yaml_file(path);
  const YAML::Node sweep = root.IsMap() ? root["sweep"] : YAML::Node();
  if (!sweep) fail("{}: sweep: required key missing (a sweep file lists the values to vary, e.g. sweep: {{bv.k: [6, 18]}})", path);
  if (!sweep.IsMap()) fail("{}: sweep: expected a map of dotted config keys to lists of values", where(path, sweep));

  SweepPlan plan;
  plan.source = path;
  std::vector<Axis> axes;
  for (const auto& kv : sweep) {
    const std::string key = kv.first.as<std::string>();
    if (key == "repeats") {
      try {
        plan.repeats = kv.second.as<int>();
      } catch (const YAML::Exception&) {
        fail("{}: sweep.repeats: expected an integer from 1 to 1000, got '{}'", where(path, kv.second),
             as_override_text(kv.second));
      }
      if (plan.repeats < 1 || plan.repeats > 1000)
        fail("{}: sweep.repeats: expected an integer from 1 to 1000, got {}", where(path, kv.second), plan.repeats);
    } else if (key == "zip") {
      if (!kv.second.IsMap() || kv.second.size() == 0)
        fail("{}: sweep.zip: expected a map of dotted keys to lists of one length", where(path, kv.second));
      Axis axis;
      for (const auto& z : kv.second) {
        const std::string zkey = z.first.as<std::string>();
        axis.keys.push_back(zkey);
        axis.values.push_back(values_of(path, "zip." + zkey, z.second));
        if (axis.values.back().size() != axis.values.front().size())
          fail("{}: sweep.zip.{}: {} values, but sweep.zip.{} has {} (zipped lists go together: one length)",
               where(path, z.second), zkey, axis.values.back().size(), axis.keys.front(), axis.values.front().size());
      }
      axes.push_back(std::move(axis));
    } else {
      axes.push_back(Axis{{key}, {values_of(path, key, kv.second)}});
    }
  }
  for (const Axis& a : axes)
    for (const std::string& k : a.keys) {
      for (const std::string& seen : plan.keys)
        if (seen == k) fail("{}: sweep: key '{}' is varied twice", path, k);
      plan.keys.push_back(k);
    }

  // The base config (every run's output.dir lies under its output.dir).
  const ExperimentConfig base = load_experiment(path, overrides, registries, /*sweep_allowed=*/true);
  plan.output_dir = base.output.dir;

  plan.combinations = 1;
  for (const Axis& a : axes) plan.combinations *= a.size();
  struct Combination {
    std::vector<std::string> sets;
    std::string label, hash;
    ExperimentConfig config;
  };
  std::vector<Combination> combos(plan.combinations);
  for (std::size_t c = 0; c < plan.combinations; ++c) {
    // Mixed radix, the last axis fastest.
    std::vector<std::size_t> pick(axes.size());
    for (std::size_t a = axes.size(), rest = c; a-- > 0;) {
      pick[a] = rest % axes[a].size();
      rest /= axes[a].size();
    }
    Combination& combo = combos[c];
    combo.sets = overrides;
    for (std::size_t a = 0; a < axes.size(); ++a)
      for (std::size_t k = 0; k < axes[a].keys.size(); ++k) {
        const std::string assignment = axes[a].keys[k] + "=" + as_override_text(axes[a].values[k][pick[a]]);
        combo.sets.push_back(assignment);
        combo.label += (combo.label.empty() ? "" : ",") + assignment;
      }
    try {
      combo.config = load_experiment(path, combo.sets, registries, true);
    } catch (const Error& e) {
      fail("{}: sweep: run {} ({}): {}", path, c, combo.label.empty() ? "base" : combo.label, e.what());
    }
    nlohmann::json j = to_json(combo.config);
    j.erase("output");
    j.erase("memory_limit_bytes");  // resolved from this machine's memory: the same run on every machine
    combo.hash = fmt::format("{:016x}", fnv1a(j.dump()));
  }
  for (int r = 0; r < plan.repeats; ++r)
    for (std::size_t i = 0; i < plan.combinations; ++i) {
      const std::size_t c = r % 2 == 0 ? i : plan.combinations - 1 - i;
      SweepRun run;
      run.index = plan.runs.size();
      run.repeat = r;
      run.combination = c;
      run.overrides = combos[c].sets;
      run.label = combos[c].label;
      run.config_hash = combos[c].hash;
      run.dir = (std::filesystem::path(plan.output_dir) / (folder_label(run.label) + "-" + run.config_hash) /
                 fmt::format("rep{}", r))
                    .string();
      run.config = combos[c].config;
      run.config.output.dir = run.dir;
      plan.runs.push_back(std::move(run));
    }
  return plan;
}

}  // namespace ccdlab
