/// @file mjcf_fuzzer.cpp
/// libFuzzer target for the MJCF importer (mjcf_import.h, load_mjcf): the input is an MJCF file.
/// A model that imports is also built into a scene, which runs the articulation checks on the
/// bots the importer produced.

#include "fuzz_input.h"
#include "superdex/physics/engine.h"
#include "superdex/robotics/context.h"
#include "superdex/robotics/mjcf_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace sdp = superdex::physics;
  namespace sdr = superdex::robotics;
  static const bool initialized = (sdp::initialize(0), true);
  (void)initialized;
  const std::string path = superdex::fuzz::write_input(data, size, "input.xml");
  std::vector<std::string> warnings;
  sdp::Scene scene = sdp::create_scene("fuzz");
  superdex::fuzz::expect_error_or_success([&] {
    const sdr::MjcfModel model = sdr::load_mjcf(path, &warnings);
    sdr::Context context;
    for (const sdr::BotPrefab& prefab : model.bots) context.create_bot(scene, prefab, &warnings);
  });
  sdp::destroy_scene(scene.handle());
  return 0;
}
