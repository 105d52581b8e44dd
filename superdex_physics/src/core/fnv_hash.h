#pragma once
// 64-bit FNV-1a hashing of byte streams: cache keys and content identities (not cryptographic).

#include <cstddef>
#include <cstdint>

namespace superdex::physics {

/// FNV-1a over bytes fed in any number of pieces; `value` is the hash of everything fed so far.
struct Fnv1a64 {
  std::uint64_t value = 14695981039346656037ull;

  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) value = (value ^ p[i]) * 1099511628211ull;
  }
};

}  // namespace superdex::physics
