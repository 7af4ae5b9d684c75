#include "framework/config/yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "framework/util/files.hpp"

namespace ccdlab {
namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a list";
  return fmt::format("'{}'", node.Scalar());
}

}  // namespace

std::string YamlReader::where(const YAML::Node& node, const std::string& path) const {
  if (from_command_line(path)) return fmt::format("--set {}", path);
  if (node.IsDefined() && node.Mark().line >= 0) return fmt::format("{}:{}", file_, node.Mark().line + 1);
  return file_;
}

bool YamlReader::from_command_line(const std::string& path) const {
  for (const auto& o : overridden_)
    if (path == o || path.starts_with(o + ".")) return true;
  return false;
}

void YamlReader::error(const YAML::Node& node, const std::string& path, const std::string& expected) const {
  fail("{}: {}: expected {}, got {}", where(node, path), path, expected, describe(node));
}

void YamlReader::require_map(const YAML::Node& node, const std::string& path) const {
  if (!node.IsMap()) error(node, path, "a map");
}

void YamlReader::check_keys(const YAML::Node& map, const std::string& path, const std::vector<std::string>& allowed) const {
  require_map(map, path);
  for (const auto& kv : map) {
    std::string key = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string full = path.empty() ? key : path + "." + key;
    std::string hint;
    std::size_t best = std::numeric_limits<std::size_t>::max();
    for (const auto& a : allowed) {
      std::size_t d = edit_distance(key, a);
      if (d < best && d <= std::max<std::size_t>(1, a.size() / 3)) best = d, hint = fmt::format(" (did you mean '{}'?)", a);
    }
    fail("{}: {}: unknown key{}; valid keys are: {}", where(kv.first, full), full, hint, fmt::join(allowed, ", "));
  }
}

long long YamlReader::integer(const YAML::Node& node, const std::string& path, double min, double max) const {
  long long v = 0;
  if (!node.IsScalar() || !YAML::convert<long long>::decode(node, v)) error(node, path, "an integer");
  if (v < min || v > max) error(node, path, fmt::format("an integer in [{}, {}]", min, max));
  return v;
}

double YamlReader::real(const YAML::Node& node, const std::string& path, double min, double max) const {
  double v = 0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, v) || !std::isfinite(v)) error(node, path, "a finite number");
  if (v < min || v > max) error(node, path, fmt::format("a number in [{}, {}]", min, max));
  return v;
}

bool YamlReader::boolean(const YAML::Node& node, const std::string& path) const {
  bool v = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, v)) error(node, path, "true or false");
  return v;
}

std::string YamlReader::string(const YAML::Node& node, const std::string& path) const {
  if (!node.IsScalar() || node.Scalar().empty()) error(node, path, "a string");
  return node.Scalar();
}

ParamValues::Value YamlReader::param(const YAML::Node& node, const std::string& path, const ParamSpec& spec) const {
  switch (spec.type) {
    case ParamType::integer: return integer(node, path, spec.min, spec.max);
    case ParamType::real: return real(node, path, spec.min, spec.max);
    case ParamType::boolean: return boolean(node, path);
    case ParamType::string: {
      std::string v = string(node, path);
      if (!spec.choices.empty() && std::find(spec.choices.begin(), spec.choices.end(), v) == spec.choices.end())
        error(node, path, fmt::format("one of {}", fmt::join(spec.choices, ", ")));
      return v;
    }
  }
  return {};
}

namespace {

/// Fails at the second of two equal keys in any mapping under `node` (`path`: the dotted keys down to it).
void reject_duplicate_keys(const YAML::Node& node, const std::string& path, const std::string& where) {
  if (node.IsSequence())
    for (std::size_t i = 0; i < node.size(); ++i) reject_duplicate_keys(node[i], fmt::format("{}[{}]", path, i), where);
  if (!node.IsMap()) return;
  std::map<std::string, int> first_line;
  for (const auto& kv : node) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string();
    const std::string full = path.empty() ? key : path + "." + key;
    const int line = kv.first.Mark().line + 1;
    if (!key.empty()) {
      const auto [seen, added] = first_line.emplace(key, line);
      if (!added) fail("{}:{}: {}: given twice (first at line {}); give each key once", where, line, full, seen->second);
    }
    reject_duplicate_keys(kv.second, full, where);
  }
}

}  // namespace

YAML::Node parse_yaml(const std::string& text, const std::string& where) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    fail("{}:{}: YAML syntax error: {}", where, e.mark.line + 1, e.msg);
  }
  reject_duplicate_keys(root, "", where);
  return root;
}

YAML::Node load_yaml_file(const std::string& path) {
  return parse_yaml(read_file(path), path);  // read_file names a missing file, a directory, an unreadable file
}

std::string apply_override(YAML::Node& root, const std::string& assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) fail("--set {}: expected key=value", assignment);
  std::string path = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::ParserException& e) {
    fail("--set {}: value is not valid YAML: {}", path, e.msg);
  }
  std::vector<std::string> keys;
  for (std::size_t start = 0;;) {
    auto dot = path.find('.', start);
    keys.push_back(path.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  for (const auto& k : keys)
    if (k.empty()) fail("--set {}: empty key in dotted path", path);
  // Walk with explicit node copies (yaml-cpp nodes are handles): create maps on the way.
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node parent = chain.back();
    YAML::Node child = parent[keys[i]];
    if (child.IsScalar()) {
      YAML::Node m(YAML::NodeType::Map);
      m["name"] = child.Scalar();
      parent[keys[i]] = m;
      child = parent[keys[i]];
    } else if (!child.IsDefined() || child.IsNull()) {
      parent[keys[i]] = YAML::Node(YAML::NodeType::Map);
      child = parent[keys[i]];
    } else if (!child.IsMap()) {
      fail("--set {}: '{}' is not a map", path, keys[i]);
    }
    chain.push_back(child);
  }
  YAML::Node last = chain.back();
  if (last[keys.back()].IsMap() && value.IsScalar() && keys.back() != "name" && last[keys.back()]["name"]) {
    // --set scheduler=phc on a map form: replace the name, keep the parameters only if the name is unchanged.
    if (last[keys.back()]["name"].Scalar() != value.Scalar()) last[keys.back()] = value;
  } else {
    last[keys.back()] = value;
  }
  return path;
}

}  // namespace ccdlab
