// The engine-wide id counter (handles.h), shared by both precisions' builds.

#include <atomic>

#include "superdex/physics/handles.h"

namespace superdex::physics {

std::int64_t next_handle() {
  static std::atomic<std::int64_t> counter{0};
  return ++counter;
}

}  // namespace superdex::physics
