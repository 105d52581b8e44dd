/// @file mesh_fuzzer.cpp
/// libFuzzer target for the mesh readers (mesh_io.h). Built four times, as obj_fuzzer,
/// stl_fuzzer, ply_fuzzer and off_fuzzer, with SUPERDEX_FUZZ_MESH_EXT naming the extension that
/// read_mesh_file dispatches on. A mesh that reads is also put through the edge checks the
/// shape builders run on it (closedness, volume).

#include "fuzz_input.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace superdex::physics;
  const std::string path = superdex::fuzz::write_input(data, size, "input" SUPERDEX_FUZZ_MESH_EXT);
  superdex::fuzz::expect_error_or_success([&] {
    const TriangleMesh mesh = read_mesh_file(path);
    if (is_closed(mesh)) (void)signed_volume(mesh);
  });
  return 0;
}
