#pragma once
// Reads typed values out of a YAML tree with located errors: "file:line: key.path: expected …, got …".
// Values set on the command line (--set a.b=v) carry no file position; their errors say "--set a.b".
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "framework/config/registry.hpp"

namespace ccdlab {

class YamlReader {
 public:
  YamlReader(std::string file, std::set<std::string> overridden) : file_(std::move(file)), overridden_(std::move(overridden)) {}

  /// "file:line" of a node, or "--set path" for a command-line value.
  [[nodiscard]] std::string where(const YAML::Node& node, const std::string& path) const;
  /// True when the node's value came from --set (paths then resolve against the working directory).
  [[nodiscard]] bool from_command_line(const std::string& path) const;
  [[noreturn]] void error(const YAML::Node& node, const std::string& path, const std::string& expected) const;

  /// Rejects keys of a map not in `allowed` (with a "did you mean" hint).
  void check_keys(const YAML::Node& map, const std::string& path, const std::vector<std::string>& allowed) const;
  void require_map(const YAML::Node& node, const std::string& path) const;

  [[nodiscard]] long long integer(const YAML::Node& node, const std::string& path, double min, double max) const;
  [[nodiscard]] double real(const YAML::Node& node, const std::string& path, double min, double max) const;
  [[nodiscard]] bool boolean(const YAML::Node& node, const std::string& path) const;
  [[nodiscard]] std::string string(const YAML::Node& node, const std::string& path) const;

  /// A strategy given as a name or as a map {name: …, param: …}, validated against its registry entry.
  /// A map without 'name' means `default_name` (so `--set tester.thickness=…` works on the default tester).
  template <class Product>
  StrategyChoice strategy(const YAML::Node& node, const std::string& path, const Registry<Product>& registry,
                          const std::string& default_name) const {
    std::string name;
    if (node.IsMap()) {
      name = node["name"] ? string(node["name"], path + ".name") : default_name;
    } else {
      name = string(node, path);
    }
    const auto* entry = registry.find(name);
    if (!entry && node.IsMap() && !node["name"])
      error(node, path, fmt::format("a map with key 'name' (one of: {})", fmt::join(registry.names(), ", ")));
    if (!entry)
      error(node.IsMap() ? node["name"] : node, node.IsMap() ? path + ".name" : path,
            fmt::format("one of {}", fmt::join(registry.names(), ", ")));
    StrategyChoice choice{name, entry->defaults()};
    if (node.IsMap()) {
      std::vector<std::string> allowed{"name"};
      for (const auto& p : entry->params) allowed.push_back(p.name);
      check_keys(node, path, allowed);
      for (const auto& p : entry->params)
        if (node[p.name]) choice.params.set(p.name, param(node[p.name], path + "." + p.name, p));
    }
    return choice;
  }

  /// Reads a parameter for its spec (type and range).
  [[nodiscard]] ParamValues::Value param(const YAML::Node& node, const std::string& path, const ParamSpec& spec) const;

 private:
  std::string file_;
  std::set<std::string> overridden_;
};

/// Parses YAML text from `where` (a file's name, or what stands for one); a syntax error, or a key given twice
/// in one mapping (YAML would keep one of them silently), becomes Error("where:line: …").
YAML::Node parse_yaml(const std::string& text, const std::string& where);

/// Loads a YAML file with parse_yaml.
YAML::Node load_yaml_file(const std::string& path);

/// Applies "a.b.c=value" to a tree (value parsed as YAML). A scalar standing where a map is needed becomes
/// {name: scalar}, so `--set scheduler.c=4` works on `scheduler: phc`. Returns the dotted path.
std::string apply_override(YAML::Node& root, const std::string& assignment);

}  // namespace ccdlab
