// The settings table (framework/config/settings.def): every row reachable from every entry point under its own
// name, every default read back unchanged, every wrong value refused naming where it came from, and docs/config.md
// holding the table the rows print.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "framework/config/settings.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

std::string error_of(const auto& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Settings, EveryRowHasItsOwnKeyFlagAndKeyword) {
  std::set<std::string_view> keys, flags, members;
  for (const Setting& s : settings()) {
    EXPECT_TRUE(keys.insert(s.key).second) << s.key;
    EXPECT_TRUE(flags.insert(s.flag_name()).second) << s.flag;
    EXPECT_TRUE(members.insert(s.member).second) << s.member;
    EXPECT_TRUE(s.flag_name().starts_with("--")) << s.flag;
    EXPECT_FALSE(s.doc.empty()) << s.key;
    EXPECT_EQ(setting_of_key(s.key), &s);
    EXPECT_EQ(setting_of_member(s.member), &s);
  }
  EXPECT_EQ(setting_of_key("bv.kk"), nullptr);
  EXPECT_EQ(setting_of_member("kk"), nullptr);
}

TEST(Settings, DefaultsAreTheFieldsOwnAndReadBackUnchanged) {
  const Registries reg = builtin_registries();
  const PipelineConfig c = default_config(reg);
  EXPECT_EQ(c.k, PipelineSettings{}.k);
  EXPECT_EQ(c.candidate_limit, PipelineSettings{}.candidate_limit);
  EXPECT_EQ(c.narrow.rules, StageRuleChoices{});
  EXPECT_EQ(c.tester.params.all(), tester_registry().find(kDefaultTester)->defaults().all());
  EXPECT_GT(c.memory_limit_bytes, 0u);
  const nlohmann::json want = settings_json(c);
  for (const Setting& s : settings()) {
    // Each entry point's path: the value as Options / the CLI hold it, and the YAML the resolved config writes.
    PipelineConfig by_value = c;
    s.set(by_value, s.value(c), reg, "x");
    EXPECT_EQ(settings_json(by_value), want) << s.key;
    PipelineConfig by_text = c;
    const std::string text = std::visit([](const auto& v) { return fmt::format("{}", v); }, s.value(c));
    s.set(by_text, setting_value_of_text(s, text, "x"), reg, "x");
    EXPECT_EQ(settings_json(by_text), want) << s.key << " from '" << text << "'";
  }
  PipelineConfig by_yaml = c;
  read_settings(YamlReader("resolved", {}), parse_yaml(to_yaml(want), "resolved"), reg, by_yaml);
  EXPECT_EQ(settings_json(by_yaml), want);
}

TEST(Settings, AValueSetThroughItsRowIsTheOneTheYamlKeyGives) {
  const Registries reg = builtin_registries();
  const std::vector<std::pair<std::string, std::string>> given{
      {"bv.k", "14"}, {"bv.end_boxes", "off"}, {"hierarchy", "sah:bins=32"}, {"restructure.threshold", "1.5"},
      {"normal_cones", "true"}, {"scheduler", "phc:c=4"}, {"tester", "conservative:delta=1e-4"},
      {"narrow.rules.proximity", "on"}, {"memory_limit", "2GiB"}, {"candidate_limit", "50"}};
  for (const auto& [key, text] : given) {
    const Setting& s = *setting_of_key(key);
    PipelineConfig flag = default_config(reg), yaml = default_config(reg);
    s.set(flag, setting_value_of_text(s, text, "x"), reg, "x");
    YAML::Node root(YAML::NodeType::Map);
    apply_override(root, key + "=" + text);
    read_settings(YamlReader("given", {}), root, reg, yaml);
    EXPECT_EQ(settings_json(flag), settings_json(yaml)) << key;
    EXPECT_NE(settings_json(flag), settings_json(default_config(reg))) << key << ": " << text << " is its default";
  }
}

TEST(Settings, AWrongValueIsRefusedUnderTheNameItCameBy) {
  const Registries reg = builtin_registries();
  for (const Setting& s : settings()) {
    PipelineConfig c = default_config(reg);
    const std::string e = error_of([&] { s.set(c, std::string("??"), reg, "--the-flag"); });
    EXPECT_EQ(e.rfind("--the-flag", 0), 0u) << s.key << ": " << e;
    // YAML: a list where a value belongs, located at its line.
    std::string yaml = "threads: 1\n", indent;
    const std::string key(s.key);
    for (std::size_t pos = 0, dot; (dot = key.find('.', pos)) != std::string::npos; pos = dot + 1) {
      yaml += indent + key.substr(pos, dot - pos) + ":\n";
      indent += "  ";
    }
    yaml += indent + key.substr(key.rfind('.') + 1) + ": [1, 2]\n";
    const int line = int(std::count(yaml.begin(), yaml.end(), '\n'));
    PipelineConfig y = default_config(reg);
    const std::string ey = error_of([&] { read_settings(YamlReader("f.yaml", {}), parse_yaml(yaml, "f.yaml"), reg, y); });
    EXPECT_NE(ey.find(fmt::format("f.yaml:{}: {}", line, s.key)), std::string::npos) << yaml << ey;
  }
  EXPECT_EQ(error_of([&] {
              PipelineConfig c = default_config(reg);
              setting_of_member("k")->set(c, 7LL, reg, "Options::k");
            }),
            "Options::k: expected one of 6, 14, 18, 26, got 7");
  EXPECT_NE(error_of([&] {
              PipelineConfig c = default_config(reg);
              read_settings(YamlReader("f.yaml", {}), parse_yaml("narrow:\n  rules:\n    proximty: on\n", "f.yaml"), reg, c);
            }).find("f.yaml:3: narrow.rules.proximty: unknown key (did you mean 'proximity'?)"),
            std::string::npos);
}

TEST(Settings, DocsConfigHoldsTheTableTheRowsPrint) {
  // docs/config.md shows the table `ccdlab list --settings` prints; a row added or changed fails here until the
  // docs follow (paste the command's output between the markers).
  std::ifstream in(std::string(CCDLAB_SOURCE_DIR) + "/docs/config.md");
  ASSERT_TRUE(in) << "docs/config.md";
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(settings_markdown(builtin_registries())), std::string::npos)
      << "docs/config.md's settings table differs from `build/bin/ccdlab list --settings`:\n"
      << settings_markdown(builtin_registries());
}

}  // namespace
}  // namespace ccdlab
