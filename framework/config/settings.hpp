#pragma once
// The settings table (settings.def) as rows a program can walk: every entry point reads and writes the pipeline's
// settings through these — the YAML reader and the resolved config's writer (experiment.cpp), the CLI's flags
// (experiments/cli), the C++ API's Options (framework/api) and the Python module's keywords — and docs/config.md's
// table is printed from them (`ccdlab settings`), so adding a setting is one row plus the code that uses it.
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "framework/config/pipeline_config.hpp"
#include "framework/config/yaml_reader.hpp"

namespace ccdlab {

/// How a row's value is read (settings.def's first column).
enum class SettingKind { plain, choice, strategy, memory };

/// A value as an entry point holds it before its row reads it: a YAML or CLI text, a Python object, an Options
/// member (integers widened).
using SettingValue = std::variant<bool, long long, double, std::string>;

struct Setting {
  SettingKind kind;
  std::string_view member;  ///< the C++ Options member and the Python keyword
  std::string_view type;    ///< the member's C++ type: int, double, bool, std::string
  std::string_view key;     ///< the YAML key path, e.g. "bv.k"
  std::string_view flag;    ///< the CLI flag as CLI11 takes it ("--end-boxes{on}": a bare flag means on)
  std::string_view doc;     ///< one line

  /// Sets the row's field of `c` from an entry point's value; throws Error "<name>: expected …, got …".
  void (*set)(PipelineConfig& c, const SettingValue& v, const Registries& reg, const std::string& name);
  /// Sets the row's field of `c` from its node in a YAML tree; errors are located by `r` (file:line or --set).
  void (*read)(const YamlReader& r, const YAML::Node& node, PipelineConfig& c, const Registries& reg);
  /// The row's value in `c` as Options holds it (a strategy as "name:key=value,…").
  SettingValue (*value)(const PipelineConfig& c);
  /// The row's value in `c` as the resolved config writes it (a strategy as a map with every parameter).
  nlohmann::json (*json)(const PipelineConfig& c);
  /// What the row accepts, as messages and docs say it ("one of 6, 14, 18, 26"; "on, off, auto, true or false").
  std::string (*accepts)(const Registries& reg);

  /// The flag without CLI11's bare-flag value: "--end-boxes".
  [[nodiscard]] std::string_view flag_name() const { return flag.substr(0, flag.find('{')); }
};

/// Every row, in settings.def's order.
[[nodiscard]] std::span<const Setting> settings();
/// The row of a YAML key path or of an Options member / Python keyword; nullptr when there is none.
[[nodiscard]] const Setting* setting_of_key(std::string_view key);
[[nodiscard]] const Setting* setting_of_member(std::string_view member);
/// "k, width, end_boxes, …": the members, for an "unknown option" message.
[[nodiscard]] std::string setting_members();

/// How an entry point spells a setting in messages (PipelineSettings::validate's SettingName): YAML its key,
/// the CLI its flag, the C++ API "Options::member", the Python module "<call>: member".
enum class SettingSpelling { key, flag, member };
[[nodiscard]] SettingName setting_name(SettingSpelling spelling, std::string prefix = {});

/// The configuration every entry point starts from: each field's default, the strategies' parameters from their
/// registries, the memory limit resolved on this machine.
[[nodiscard]] PipelineConfig default_config(const Registries& reg);

/// The settings' top-level keys (bv, hierarchy, …): what a root map may hold besides its own keys.
[[nodiscard]] std::vector<std::string> setting_roots();
/// Reads the settings of a YAML map (an experiment's root, Options::from_yaml's text) into `c`, checking the keys
/// of their sections (bv, narrow, …); the caller checks the root's own (setting_roots).
void read_settings(const YamlReader& r, const YAML::Node& root, const Registries& reg, PipelineConfig& c);
/// The settings of `c` as the resolved config writes them, plus the memory limit resolved to bytes.
[[nodiscard]] nlohmann::json settings_json(const PipelineConfig& c);

/// A value as a message shows it ("got 0", "got 'abc'").
[[nodiscard]] std::string describe(const SettingValue& v);
/// A command line's text as the row's type reads it (an integer, a number, true / false, or the text itself);
/// throws Error "<name>: expected an integer, got 'x'".
[[nodiscard]] SettingValue setting_value_of_text(const Setting& s, const std::string& text, const std::string& name);

/// docs/config.md's table of settings (Markdown), made from the rows; a test compares the two.
[[nodiscard]] std::string settings_markdown(const Registries& reg);

}  // namespace ccdlab
