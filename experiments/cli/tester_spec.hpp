#pragma once
// The --tester option of `step` and `validate`: "NAME" or "NAME:key=value,key=value", validated against the
// tester registry like a YAML `tester:` map (errors name the argument).
#include <string>

#include "framework/config/registry.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {

StrategyChoice parse_tester(const std::string& spec, const TesterRegistry& registry);

}  // namespace ccdlab::cli
