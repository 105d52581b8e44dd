#pragma once
/// @file error.h
/// The one exception type of the engine. Python sees it as `superdex.physics.Error`.

#include <stdexcept>
#include <string>

namespace superdex {

/// Raised for every user-facing failure: bad input (the message names the file, field,
/// argument or index and what was expected), unknown handles, and numerical faults.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace superdex
