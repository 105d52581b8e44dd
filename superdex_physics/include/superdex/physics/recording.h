#pragma once
/// Recording of simulation runs for the scene debugger: every step of every live scene, decimated
/// to a frame interval, written as JSON lines (format: docs/recording_format.md). The debugger
/// replays a recording with no simulation running; without a display, `debugger.attach()` records
/// to a file instead of serving the page.

#include <string>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Starts recording to `path` (overwritten): a header, each scene and actor when first seen, then
/// a frame whenever at least `frame_interval` seconds (>= 0; 0 = every step) of simulated time
/// passed since a scene's last frame. Throws superdex::Error if the file cannot be written or a
/// recording is already running.
void start_recording(const std::string& path, double frame_interval);
/// Flushes and closes the recording; no effect when none is running.
void stop_recording();
/// Whether a recording is running.
bool is_recording();
/// The most simulated time (s) a recorded scene has run since the recording started: the sum of
/// its step sizes (a restored state rewinds the scene's clock, not this); 0 before the first step.
double recorded_time();
/// How many frames the running recording has written (0 when none runs).
long long recorded_frames();
/// The recording's path ("" when none).
std::string recording_path();

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
