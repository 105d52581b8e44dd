#pragma once
/// @file handles.h
/// Integer handles: every scene, shape and actor gets a distinct positive id drawn from one
/// engine-wide counter; ids are never reused, so a stale handle is always detected.

#include <cstdint>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using SceneHandle = std::int64_t;
using ShapeHandle = std::int64_t;
using ActorHandle = std::int64_t;

/// The next unused handle (thread-safe).
std::int64_t next_handle();

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
