#pragma once
// Base64 (RFC 4648, with padding) of binary data, for files embedded in JSON lines.

#include <string>
#include <string_view>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::string base64_encode(std::string_view bytes);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
