/// @file prefab_json_fuzzer.cpp
/// libFuzzer target for the prefab loader (prefab.h, prefab::add_to_scene from a file): the input is a
/// `.mochi_prefab` file, loaded into a fresh scene with the scratch folder as the root (so the
/// files it names are looked up there, the input itself included).

#include "fuzz_input.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/prefab.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace sdp = superdex::physics;
  static const bool initialized = (sdp::initialize(0), true);
  (void)initialized;
  const std::string path = superdex::fuzz::write_input(data, size, "input.mochi_prefab");
  std::vector<std::string> warnings;
  sdp::Scene scene = sdp::create_scene("fuzz");
  superdex::fuzz::expect_error_or_success([&] {
    sdp::prefab::PrefabParams params;
    params.apply_scene_settings = true;
    (void)sdp::prefab::add_to_scene(path, superdex::fuzz::scratch_dir().string(), scene, params, &warnings);
  });
  sdp::destroy_scene(scene.handle());
  return 0;
}
