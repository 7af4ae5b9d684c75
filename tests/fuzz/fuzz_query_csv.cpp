// libFuzzer target: the elementary query reader (rational CSV, 6 or 7 columns). The input is one file of an
// edge-edge set; the first byte picks a 7-column (truth inside) or a 6-column file whose ground-truth JSON is
// the rest of the input after the first NUL byte, so the JSON reader is fuzzed too.
#include <algorithm>
#include <filesystem>

#include "framework/queries/query_set.hpp"
#include "fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ccdlab;
  namespace fs = std::filesystem;
  static const fs::path root = fuzz::scratch_path("queries");
  const std::uint8_t* nul = std::find(data, data + size, std::uint8_t(0));
  const std::string csv(reinterpret_cast<const char*>(data), std::size_t(nul - data));
  const std::string json = nul < data + size ? std::string(reinterpret_cast<const char*>(nul + 1), std::size_t(data + size - nul - 1)) : "";
  fs::create_directories(root / "queries");
  fs::create_directories(root / "mma_bool");
  std::ofstream(root / "queries" / "input_ee.csv", std::ios::binary) << csv;
  std::ofstream(root / "mma_bool" / "input_ee_mma_bool.json", std::ios::binary) << json;
  return fuzz::expect_result_or_error([&] { (void)load_query_sets(root / "queries" / "input_ee.csv"); });
}
