#pragma once
// A registry per interface: name → one-line description, parameter specs (with defaults and ranges) and a
// factory. It drives YAML validation ("valid values are: …"), `ccdlab list`, and construction.
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "framework/util/error.hpp"

namespace ccdlab {

enum class ParamType { integer, real, boolean, string };

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::real;
  std::variant<long long, double, bool, std::string> default_value;
  std::string description;
  double min = -std::numeric_limits<double>::infinity();  ///< for integer and real
  double max = std::numeric_limits<double>::infinity();
  std::vector<std::string> choices = {};  ///< for string parameters: the valid values (empty = any)
};

std::string_view to_string(ParamType type);
/// The default value of a spec as text ("0.5", "true", "median").
std::string default_text(const ParamSpec& spec);

/// Typed parameter values of one strategy instance: defaults overridden by the config.
class ParamValues {
 public:
  using Value = std::variant<long long, double, bool, std::string>;
  void set(const std::string& name, Value v) { values_[name] = std::move(v); }
  [[nodiscard]] long long integer(const std::string& name) const { return get<long long>(name); }
  [[nodiscard]] double real(const std::string& name) const { return get<double>(name); }
  [[nodiscard]] bool boolean(const std::string& name) const { return get<bool>(name); }
  [[nodiscard]] const std::string& string(const std::string& name) const { return get<std::string>(name); }
  [[nodiscard]] const std::map<std::string, Value>& all() const { return values_; }

 private:
  template <class T>
  const T& get(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end() || !std::holds_alternative<T>(it->second))
      fail("internal: parameter '{}' missing or of another type", name);
    return std::get<T>(it->second);
  }
  std::map<std::string, Value> values_;
};

/// A strategy chosen by name with its parameters (what YAML `tester: {name: float, thickness: 0}` becomes).
struct StrategyChoice {
  std::string name;
  ParamValues params;
};

template <class Product>
struct RegistryEntry {
  std::string name;
  std::string description;
  std::vector<ParamSpec> params;
  std::function<Product(const ParamValues&)> make;
  /// Optional, for scenes: how many triangles `make` will produce, known before making it (so that a run too
  /// large for memory_limit is refused at once rather than after the scene is built).
  std::function<std::uint64_t(const ParamValues&)> triangles{};

  /// Values holding every parameter's default.
  [[nodiscard]] ParamValues defaults() const {
    ParamValues v;
    for (const auto& p : params) v.set(p.name, p.default_value);
    return v;
  }
};

template <class Product>
class Registry {
 public:
  explicit Registry(std::string kind) : kind_(std::move(kind)) {}
  void add(RegistryEntry<Product> entry) { entries_.push_back(std::move(entry)); }
  [[nodiscard]] const std::string& kind() const { return kind_; }
  [[nodiscard]] const std::vector<RegistryEntry<Product>>& entries() const { return entries_; }
  [[nodiscard]] const RegistryEntry<Product>* find(const std::string& name) const {
    for (const auto& e : entries_)
      if (e.name == name) return &e;
    return nullptr;
  }
  [[nodiscard]] std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }
  /// Builds the product of a choice; throws Error naming the valid values for an unknown name.
  [[nodiscard]] Product make(const StrategyChoice& choice) const {
    const auto* e = find(choice.name);
    if (!e) fail("{}: unknown '{}', valid values are: {}", kind_, choice.name, fmt::join(names(), ", "));
    return e->make(choice.params);
  }

 private:
  std::string kind_;
  std::vector<RegistryEntry<Product>> entries_;
};

}  // namespace ccdlab
