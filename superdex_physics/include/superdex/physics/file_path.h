#pragma once
/// @file file_path.h
/// Questions about paths named in user files, answered without throwing.

#include <filesystem>
#include <system_error>

namespace superdex {

/// True when `path` names an existing regular file (after following links). A path the
/// system cannot look up (too long, a component that is not a directory, no permission)
/// is not a file: the caller reports it with the field that named it, rather than letting
/// std::filesystem throw.
inline bool is_existing_file(const std::filesystem::path& path) noexcept {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) && !ec;
}

}  // namespace superdex
