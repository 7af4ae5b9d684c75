#include "experiments/cli/tester_spec.hpp"

#include <yaml-cpp/yaml.h>

#include "framework/config/yaml_reader.hpp"
#include "framework/util/error.hpp"

namespace ccdlab::cli {

StrategyChoice parse_tester(const std::string& spec, const TesterRegistry& registry) {
  YAML::Node node(YAML::NodeType::Map);
  const auto colon = spec.find(':');
  node["name"] = spec.substr(0, colon);
  if (colon != std::string::npos) {
    std::string rest = spec.substr(colon + 1);
    std::size_t pos = 0;
    while (pos <= rest.size()) {
      const std::size_t comma = std::min(rest.find(',', pos), rest.size());
      const std::string kv = rest.substr(pos, comma - pos);
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) fail("--tester {}: expected name:key=value,…, got '{}'", spec, kv);
      node[kv.substr(0, eq)] = kv.substr(eq + 1);  // a plain scalar: no file position in errors
      pos = comma + 1;
    }
  }
  YamlReader reader("--tester " + spec, {});
  return reader.strategy(node, "tester", registry, "float");
}

}  // namespace ccdlab::cli
