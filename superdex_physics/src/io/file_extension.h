#pragma once
// A file's extension as the readers dispatch on it: the last one, lower case, with its dot
// (".h5" for "duck.mochi.h5"; empty when there is none).

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace superdex::physics {

inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace superdex::physics
