#pragma once
// A closed set of named values (an enum a config key takes): one table per set, which every reader (YAML, the
// CLI, the C++ API, the Python module), every message and every CLI choice list reads.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "framework/util/error.hpp"

namespace ccdlab {

template <class E>
struct NamedValue {
  std::string_view name;
  E value;
};

/// The names of a set, in table order; a value may have several (the first is the one written back).
template <class E, std::size_t N>
struct NamedValues {
  std::array<NamedValue<E>, N> table;

  [[nodiscard]] constexpr std::optional<E> find(std::string_view name) const {
    for (const NamedValue<E>& n : table)
      if (n.name == name) return n.value;
    return std::nullopt;
  }
  /// The first name of `value` (what results and to_string write).
  [[nodiscard]] constexpr std::string_view name_of(E value) const {
    for (const NamedValue<E>& n : table)
      if (n.value == value) return n.name;
    return {};
  }
  /// Every name, in table order (a CLI's choice list).
  [[nodiscard]] std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const NamedValue<E>& n : table) out.emplace_back(n.name);
    return out;
  }
  /// "a, b or c": what a message says is expected.
  [[nodiscard]] std::string expected() const {
    std::string out;
    for (std::size_t i = 0; i < N; ++i) out += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(table[i].name);
    return out;
  }
  /// The value named `name`; otherwise throws Error "field: expected a, b or c, got 'name'".
  [[nodiscard]] E parse(std::string_view name, std::string_view field) const {
    if (const std::optional<E> v = find(name)) return *v;
    fail("{}: expected {}, got '{}'", field, expected(), name);
  }
};

template <class E, class... Rest>
NamedValues(NamedValue<E>, Rest...) -> NamedValues<E, 1 + sizeof...(Rest)>;

}  // namespace ccdlab
