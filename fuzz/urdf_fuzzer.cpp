/// @file urdf_fuzzer.cpp
/// libFuzzer target for the URDF importer (bot_prefab.h, load_bot_prefab_from_urdf): the input
/// is a URDF file. A URDF that imports is also built into a scene, which runs the articulation
/// checks on what the importer produced.

#include "fuzz_input.h"
#include "superdex/physics/engine.h"
#include "superdex/robotics/bot_prefab.h"
#include "superdex/robotics/context.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace sdp = superdex::physics;
  namespace sdr = superdex::robotics;
  static const bool initialized = (sdp::initialize(0), true);
  (void)initialized;
  const std::string path = superdex::fuzz::write_input(data, size, "input.urdf");
  std::vector<std::string> warnings;
  sdp::Scene scene = sdp::create_scene("fuzz");
  superdex::fuzz::expect_error_or_success([&] {
    const sdr::BotPrefab prefab = sdr::load_bot_prefab_from_urdf(path, &warnings);
    sdr::Context context;
    context.create_bot(scene, prefab, &warnings);
  });
  sdp::destroy_scene(scene.handle());
  return 0;
}
