/// @file recording_fuzzer.cpp
/// libFuzzer target for the recording reader of the replay server (server/recording_reader.h):
/// the input is a recording file (JSON lines).

#include "fuzz_input.h"
#include "recording_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = superdex::fuzz::write_input(data, size, "input.jsonl");
  superdex::fuzz::expect_error_or_success([&] { (void)superdex::physics::debug::read_recording(path); });
  return 0;
}
