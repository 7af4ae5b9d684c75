#include "framework/config/settings.hpp"

#include <charconv>
#include <climits>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "framework/config/strategy_spec.hpp"
#include "framework/util/error.hpp"
#include "framework/util/memory.hpp"

namespace ccdlab {
namespace {

// ---- plain rows: a number or a boolean, checked by its setting_check (pipeline_settings.hpp) ----

/// The type a plain row's check reads: integers wide, so that 1e12 is "out of range" and not wrapped.
template <class T>
using Checked = std::conditional_t<std::is_same_v<T, int>, long long, T>;

template <class T>
constexpr const char* type_expected() {
  if constexpr (std::is_same_v<T, int>) return "an integer";
  else if constexpr (std::is_same_v<T, double>) return "a number";
  else return "true or false";
}

template <class T>
Checked<T> plain_value(const SettingValue& v, const std::string& name) {
  if constexpr (std::is_same_v<T, bool>) {
    if (const bool* b = std::get_if<bool>(&v)) return *b;
  } else {
    if (const long long* i = std::get_if<long long>(&v)) return Checked<T>(*i);
    if constexpr (std::is_same_v<T, double>)
      if (const double* d = std::get_if<double>(&v)) return *d;
  }
  fail("{}: expected {}, got {}", name, type_expected<T>(), describe(v));
}

template <class T>
Checked<T> yaml_value(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  if constexpr (std::is_same_v<T, int>) return r.integer(n, key, -1e18, 1e18);
  else if constexpr (std::is_same_v<T, double>) return r.real(n, key, -1e300, 1e300);
  else return r.boolean(n, key);
}

/// What a plain row accepts: its check says so for a value no setting takes (checks return the text when wrong).
template <class T, class Check>
std::string plain_accepts(Check check) {
  if constexpr (std::is_same_v<T, int>) return check(LLONG_MIN);
  else if constexpr (std::is_same_v<T, double>) return check(std::numeric_limits<double>::quiet_NaN());
  else return type_expected<T>();
}

template <class T>
SettingValue widened(T v) {
  if constexpr (std::is_same_v<T, int>) return (long long)v;
  else return v;
}

// ---- choice rows: a name of a NamedValues set (YAML's booleans are names too: true, false) ----

std::string choice_text(const SettingValue& v, const std::string& name, const std::string& expected) {
  if (const std::string* s = std::get_if<std::string>(&v)) return *s;
  if (const bool* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  fail("{}: expected {}, got {}", name, expected, describe(v));
}

/// What a strategy's spec follows in messages: "--tester float:…" on the command line, "tester=float:…" elsewhere.
std::string spec_where(const std::string& name) { return name + (name.starts_with("--") ? " " : "="); }

constexpr const char* kMemoryExpected = "a size like 8GiB, 512MiB or 60% (of this machine's memory), or none";

// One Setting per row of settings.def, its functions made by kind (the macros below): `field` is the
// PipelineConfig member the row sets, `rule` its check, name set, registry or parser.
#define CCDLAB_ROW_plain(member, type, key, flag, field, rule, doc)                                             \
  Setting{SettingKind::plain, #member, #type, key, flag, doc,                                                   \
          [](PipelineConfig& c, const SettingValue& v, const Registries&, const std::string& name) {           \
            const auto x = plain_value<type>(v, name);                                                          \
            if (const std::string e = rule(x); !e.empty()) fail("{}: expected {}, got {}", name, e, describe(v)); \
            c.field = type(x);                                                                                  \
          },                                                                                                    \
          [](const YamlReader& r, const YAML::Node& n, PipelineConfig& c, const Registries&) {                 \
            const auto x = yaml_value<type>(r, n, key);                                                         \
            if (const std::string e = rule(x); !e.empty()) r.error(n, key, e);                                  \
            c.field = type(x);                                                                                  \
          },                                                                                                    \
          [](const PipelineConfig& c) { return widened<type>(c.field); },                                       \
          [](const PipelineConfig& c) { return nlohmann::json(c.field); },                                      \
          [](const Registries&) { return plain_accepts<type>(rule); }}

#define CCDLAB_ROW_choice(member, type, key, flag, field, rule, doc)                                             \
  Setting{SettingKind::choice, #member, #type, key, flag, doc,                                                  \
          [](PipelineConfig& c, const SettingValue& v, const Registries&, const std::string& name) {           \
            c.field = rule.parse(choice_text(v, name, rule.expected()), name);                                  \
          },                                                                                                    \
          [](const YamlReader& r, const YAML::Node& n, PipelineConfig& c, const Registries&) {                 \
            const auto x = rule.find(r.string(n, key));                                                         \
            if (!x) r.error(n, key, rule.expected());                                                           \
            c.field = *x;                                                                                       \
          },                                                                                                    \
          [](const PipelineConfig& c) { return SettingValue(std::string(rule.name_of(c.field))); },            \
          [](const PipelineConfig& c) { return nlohmann::json(std::string(rule.name_of(c.field))); },          \
          [](const Registries&) { return rule.expected(); }}

#define CCDLAB_ROW_strategy(member, type, key, flag, field, rule, doc)                                          \
  Setting{SettingKind::strategy, #member, #type, key, flag, doc,                                                \
          [](PipelineConfig& c, const SettingValue& v, const Registries& reg, const std::string& name) {       \
            const auto* text = std::get_if<std::string>(&v);                                                    \
            if (!text) fail("{}: expected a name or 'name:key=value,…', got {}", name, describe(v));            \
            c.field = parse_strategy_spec(*text, spec_where(name), key, reg.rule, c.field.name);               \
          },                                                                                                    \
          [](const YamlReader& r, const YAML::Node& n, PipelineConfig& c, const Registries& reg) {             \
            if (n.IsScalar() && n.Scalar().find(':') != std::string::npos) /* the one-line form */            \
              c.field = parse_strategy_spec(n.Scalar(), r.where(n, key) + ": " + key + "=", key, reg.rule,     \
                                            c.field.name);                                                      \
            else                                                                                                \
              c.field = r.strategy(n, key, reg.rule, c.field.name);                                             \
          },                                                                                                    \
          [](const PipelineConfig& c) { return SettingValue(strategy_spec_text(c.field)); },                   \
          [](const PipelineConfig& c) { return params_json(c.field); },                                         \
          [](const Registries& reg) { return fmt::format("{}", fmt::join(reg.rule.names(), ", ")); }}

#define CCDLAB_ROW_memory(member, type, key, flag, field, rule, doc)                                            \
  Setting{SettingKind::memory, #member, #type, key, flag, doc,                                                  \
          [](PipelineConfig& c, const SettingValue& v, const Registries&, const std::string& name) {           \
            const auto* text = std::get_if<std::string>(&v);                                                    \
            if (!text) fail("{}: expected {}, got {}", name, kMemoryExpected, describe(v));                     \
            c.memory_limit_bytes = rule(*text, name);                                                           \
            c.field = *text;                                                                                    \
          },                                                                                                    \
          [](const YamlReader& r, const YAML::Node& n, PipelineConfig& c, const Registries&) {                 \
            const std::string text = r.string(n, key);                                                          \
            try {                                                                                               \
              c.memory_limit_bytes = rule(text, key);                                                           \
            } catch (const Error&) {                                                                            \
              r.error(n, key, kMemoryExpected);                                                                 \
            }                                                                                                   \
            c.field = text;                                                                                     \
          },                                                                                                    \
          [](const PipelineConfig& c) { return SettingValue(c.field); },                                        \
          [](const PipelineConfig& c) { return nlohmann::json(c.field); },                                      \
          [](const Registries&) { return std::string(kMemoryExpected); }}

#define CCDLAB_SETTING(kind, member, type, key, flag, field, rule, doc) \
  CCDLAB_ROW_##kind(member, type, key, flag, field, rule, doc),
const Setting kSettings[] = {
#include "framework/config/settings.def"
};
#undef CCDLAB_SETTING

/// "bv.k" → {"bv", "k"}.
std::vector<std::string> path_of(std::string_view key) {
  std::vector<std::string> parts;
  for (std::size_t pos = 0;;) {
    const std::size_t dot = key.find('.', pos);
    parts.emplace_back(key.substr(pos, dot - pos));
    if (dot == std::string_view::npos) return parts;
    pos = dot + 1;
  }
}

/// The node at `parts` under `root`, or an undefined node. (Read through const nodes and `reset`: a YAML::Node's
/// operator[] on a non-const node adds the key, and its operator= writes into the tree.)
YAML::Node node_at(const YAML::Node& root, const std::vector<std::string>& parts) {
  YAML::Node node;
  node.reset(root);
  for (const std::string& p : parts) {
    const YAML::Node& here = node;
    if (!here.IsMap() || !here[p]) return YAML::Node(YAML::NodeType::Undefined);
    node.reset(here[p]);
  }
  return node;
}

std::string joined(const std::vector<std::string>& parts, std::size_t n) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += (i ? "." : "") + parts[i];
  return out;
}

/// A default as docs/config.md shows it: a strategy by its name (its parameters' defaults are its own table's).
std::string doc_default(const Setting& s, const PipelineConfig& c) {
  return std::visit([](const auto& x) -> std::string {
    using T = std::decay_t<decltype(x)>;
    if constexpr (std::is_same_v<T, std::string>) return x.substr(0, x.find(':'));
    else if constexpr (std::is_same_v<T, bool>) return x ? "true" : "false";
    else return fmt::format("{}", x);
  }, s.value(c));
}

}  // namespace

std::span<const Setting> settings() { return kSettings; }

const Setting* setting_of_key(std::string_view key) {
  for (const Setting& s : kSettings)
    if (s.key == key) return &s;
  return nullptr;
}

const Setting* setting_of_member(std::string_view member) {
  for (const Setting& s : kSettings)
    if (s.member == member) return &s;
  return nullptr;
}

std::string setting_members() {
  std::string out;
  for (const Setting& s : kSettings) out += (out.empty() ? "" : ", ") + std::string(s.member);
  return out;
}

SettingName setting_name(SettingSpelling spelling, std::string prefix) {
  return [spelling, prefix = std::move(prefix)](std::string_view key) {
    const Setting* s = setting_of_key(key);
    if (!s || spelling == SettingSpelling::key) return prefix + std::string(key);
    return prefix + std::string(spelling == SettingSpelling::flag ? s->flag_name() : s->member);
  };
}

PipelineConfig default_config(const Registries& reg) {
  // Each row reads back its own default: the strategies get their registries' parameters, the memory limit its
  // bytes, and every default passes its row's check.
  PipelineConfig c;
  for (const Setting& s : kSettings) s.set(c, s.value(c), reg, std::string(s.key));
  return c;
}

std::vector<std::string> setting_roots() {
  std::vector<std::string> roots;
  for (const Setting& s : kSettings) {
    const std::string root = path_of(s.key).front();
    if (std::find(roots.begin(), roots.end(), root) == roots.end()) roots.push_back(root);
  }
  return roots;
}

void read_settings(const YamlReader& r, const YAML::Node& root, const Registries& reg, PipelineConfig& c) {
  // A section (bv, narrow, narrow.rules, …) holds the next parts of its rows' keys and nothing else.
  std::map<std::string, std::vector<std::string>> sections;
  for (const Setting& s : kSettings) {
    const std::vector<std::string> parts = path_of(s.key);
    for (std::size_t n = 1; n < parts.size(); ++n) {
      auto& allowed = sections[joined(parts, n)];
      if (std::find(allowed.begin(), allowed.end(), parts[n]) == allowed.end()) allowed.push_back(parts[n]);
    }
  }
  for (const auto& [section, allowed] : sections) {
    const YAML::Node node = node_at(root, path_of(section));
    if (!node.IsDefined()) continue;
    r.require_map(node, section);
    r.check_keys(node, section, allowed);
  }
  for (const Setting& s : kSettings) {
    if (const YAML::Node node = node_at(root, path_of(s.key)); node.IsDefined()) s.read(r, node, c, reg);
  }
}

nlohmann::json settings_json(const PipelineConfig& c) {
  nlohmann::json j = nlohmann::json::object();
  for (const Setting& s : kSettings) {
    nlohmann::json* at = &j;
    for (const std::string& p : path_of(s.key)) at = &(*at)[p];
    *at = s.json(c);
  }
  j["memory_limit_bytes"] = c.memory_limit_bytes;
  return j;
}

std::string describe(const SettingValue& v) {
  return std::visit([](const auto& x) -> std::string {
    using T = std::decay_t<decltype(x)>;
    if constexpr (std::is_same_v<T, std::string>) return fmt::format("'{}'", x);
    else if constexpr (std::is_same_v<T, bool>) return x ? "true" : "false";
    else return fmt::format("{}", x);
  }, v);
}

SettingValue setting_value_of_text(const Setting& s, const std::string& text, const std::string& name) {
  if (s.type == "bool") {
    if (text == "true" || text == "on" || text == "1") return true;
    if (text == "false" || text == "off" || text == "0") return false;
    fail("{}: expected true or false, got '{}'", name, text);
  }
  if (s.type == "int") {
    long long v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size())
      fail("{}: expected an integer, got '{}'", name, text);
    return v;
  }
  if (s.type == "double") {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) fail("{}: expected a number, got '{}'", name, text);
    return v;
  }
  return text;
}

std::string settings_markdown(const Registries& reg) {
  const PipelineConfig defaults = default_config(reg);
  std::string out =
      "| key | default | accepts | CLI flag | Python keyword, `Options::` | meaning |\n"
      "|---|---|---|---|---|---|\n";
  for (const Setting& s : kSettings)
    out += fmt::format("| `{}` | `{}` | {} | `{}` | `{}` | {} |\n", s.key, doc_default(s, defaults), s.accepts(reg),
                       s.flag_name(), s.member, s.doc);
  return out;
}

}  // namespace ccdlab
