/// @file model_fuzzer.cpp
/// libFuzzer target for the model loaders (model.h). Built twice, as model_json_fuzzer and
/// model_h5_fuzzer, with SUPERDEX_FUZZ_MODEL_EXT naming the extension that model::load_from_file
/// dispatches on. A model that reads is also corrected, validated and written back as JSON.

#include "fuzz_input.h"
#include "superdex/physics/model.h"

// HDF5 sizes some allocations from the file's headers (see mochi_h5_fuzzer.cpp): let malloc
// return null under AddressSanitizer as it does without it.
extern "C" const char* __asan_default_options() { return "allocator_may_return_null=1"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace superdex::physics;
  const std::string path = superdex::fuzz::write_input(data, size, "input" SUPERDEX_FUZZ_MODEL_EXT);
  superdex::fuzz::expect_error_or_success([&] {
    ModelData model = model::load_from_file_unchecked(path);
    (void)model::save_to_json_string(model);
    model::auto_correct(model);
    model::validate(model);
  });
  return 0;
}
