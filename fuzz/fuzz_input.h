#pragma once
/// @file fuzz_input.h
/// Shared by the libFuzzer targets: the loaders read files, so each input is written to a file
/// of this process's own scratch folder under the extension the loader dispatches on, and every
/// target runs the loader through expect_error_or_success so that superdex::Error (the loaders'
/// answer to bad input) is an accepted outcome while any other exception escapes and is
/// reported by libFuzzer as a crash.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "superdex/physics/error.h"

namespace superdex::fuzz {

/// This process's scratch folder (created once; libFuzzer's -jobs run separate processes).
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("superdex_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// Writes the fuzz input to scratch_dir()/`name` and returns its path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const auto path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path.string();
}

/// Runs `load`; a superdex::Error is the expected answer to bad input and is swallowed.
template <class F>
void expect_error_or_success(F&& load) {
  try {
    load();
  } catch (const superdex::Error&) {
  }
}

}  // namespace superdex::fuzz
