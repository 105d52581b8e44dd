#pragma once
// Trying a third-party reader on an untrusted file in a child process first, so that a crash in
// the library (a corrupt file can make HDF5 read through a null pointer) becomes a
// superdex::Error for the caller instead of ending the user's process.

#include <functional>
#include <string>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Runs `attempt` once in a forked child process and returns when it finished (normally or by
/// throwing). Throws superdex::Error naming `path` when the child died by a signal, exited
/// abnormally, or did not finish within `timeout_seconds` (then it is killed). A file whose
/// contents (size and hash) already passed is not tried again.
///
/// Not thread-safe against other code of the same library: hold the library's lock around the
/// call, so that no other thread is inside it when the child is forked. The child runs only
/// `attempt` and leaves with _exit (no atexit handlers, no stdio flush).
void try_in_child_process(const std::string& path, const std::function<void()>& attempt,
                          const std::string& library, double timeout_seconds = 60.0);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
