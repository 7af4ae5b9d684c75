// libFuzzer target: the OBJ reader, then the topology checks a mesh goes through before any step.
#include "framework/mesh/mesh_io.hpp"
#include "fuzz/fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ccdlab;
  return fuzz::expect_result_or_error([&] {
    MeshData m = parse_obj(std::string(reinterpret_cast<const char*>(data), size), "input.obj");
    TriMesh mesh(m.positions.size(), std::move(m.faces));
  });
}
