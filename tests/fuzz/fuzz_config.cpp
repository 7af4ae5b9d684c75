// libFuzzer target: the experiment config loader (YAML → typed config with located errors), including the
// registry's parameter checks. A config that loads is also resolved back to JSON and YAML, as `run` does.
#include "framework/config/experiment.hpp"
#include "fuzz/fuzz_target.hpp"
#include "strategies/registry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ccdlab;
  static const Registries reg = builtin_registries();
  const std::string path = fuzz::write_input(data, size, "config.yaml");
  return fuzz::expect_result_or_error([&] {
    const ExperimentConfig c = load_experiment(path, {}, reg);
    (void)to_yaml(to_json(c));
  });
}
