// libFuzzer target: the PLY reader (ascii and binary, any header), then the topology checks.
#include "framework/mesh/mesh_io.hpp"
#include "fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ccdlab;
  return fuzz::expect_result_or_error([&] {
    MeshData m = parse_ply(std::string(reinterpret_cast<const char*>(data), size), "input.ply");
    TriMesh mesh(m.positions.size(), std::move(m.faces));
  });
}
