/// @file mochi_h5_fuzzer.cpp
/// libFuzzer target for the `.mochi.h5` reader (mochi_h5.h): the input is the bytes of an HDF5
/// file; read_mochi_h5 opens it through the HDF5 library and checks every group it holds.

#include "fuzz_input.h"
#include "superdex/physics/mochi_h5.h"

// HDF5 sizes some allocations from the file's headers and checks what malloc returns: a corrupt
// header asks for petabytes, which malloc refuses (null) in a normal process and HDF5 turns into
// an error (the loader then throws superdex::Error). AddressSanitizer aborts on such requests by
// default; let malloc return null as it does without the sanitizer. C++ allocations are not
// affected: operator new still throws, and a bad_alloc escaping the loader is still a crash.
extern "C" const char* __asan_default_options() { return "allocator_may_return_null=1"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = superdex::fuzz::write_input(data, size, "input.mochi.h5");
  superdex::fuzz::expect_error_or_success([&] { (void)superdex::physics::read_mochi_h5(path); });
  return 0;
}
