#pragma once
// A strategy written on one line — "NAME" or "NAME:key=value,key=value" (the CLI's --tester, the Python
// module's options) — validated against its registry exactly like a YAML map {name: NAME, key: value, …};
// errors name `where` followed by the spec (e.g. "--tester " or "ccdlab.step tester=") instead of a file position.
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "framework/config/yaml_reader.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {

/// "NAME[:key=value,…]" → the YAML map it stands for (values stay plain scalars, parsed by the registry's specs).
inline YAML::Node strategy_spec_node(const std::string& spec, const std::string& where) {
  YAML::Node node(YAML::NodeType::Map);
  const auto colon = spec.find(':');
  node["name"] = spec.substr(0, colon);
  if (colon == std::string::npos) return node;
  const std::string rest = spec.substr(colon + 1);
  for (std::size_t pos = 0; pos <= rest.size();) {
    const std::size_t comma = std::min(rest.find(',', pos), rest.size());
    const std::string kv = rest.substr(pos, comma - pos);
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) fail("{}{}: expected name:key=value,…, got '{}'", where, spec, kv);
    const std::string key = kv.substr(0, eq);
    if (key == "name" || std::as_const(node)[key]) fail("{}{}: '{}' is given twice; give each parameter once", where, spec, key);
    node[key] = kv.substr(eq + 1);
    pos = comma + 1;
  }
  return node;
}

/// A strategy choice from a YAML node (a name or a map), checked against `registry`; `where` names its source.
template <class Product>
StrategyChoice strategy_from_node(const YAML::Node& node, const std::string& where, const std::string& key,
                                  const Registry<Product>& registry, const std::string& default_name) {
  YamlReader reader(where, {});
  return reader.strategy(node, key, registry, default_name);
}

/// The one-line text of a choice, "name:key=value,…" (every parameter it holds): what parse_strategy_spec reads back.
inline std::string strategy_spec_text(const StrategyChoice& c) {
  std::string spec = c.name;
  char sep = ':';
  for (const auto& [key, value] : c.params.all()) {
    spec += sep + key + '=';
    std::visit([&spec](const auto& v) {
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, bool>) spec += v ? "true" : "false";
      else spec += fmt::format("{}", v);
    }, value);
    sep = ',';
  }
  return spec;
}

/// A choice as the resolved config writes it: {name: …, every parameter: value}.
inline nlohmann::json params_json(const StrategyChoice& c) {
  nlohmann::json j;
  j["name"] = c.name;
  for (const auto& [key, v] : c.params.all()) {
    const std::string& k = key;  // a structured binding cannot be captured by clang 14
    std::visit([&](const auto& x) { j[k] = x; }, v);
  }
  return j;
}

template <class Product>
StrategyChoice parse_strategy_spec(const std::string& spec, const std::string& where, const std::string& key,
                                   const Registry<Product>& registry, const std::string& default_name) {
  return strategy_from_node(strategy_spec_node(spec, where), where + spec, key, registry, default_name);
}

}  // namespace ccdlab
