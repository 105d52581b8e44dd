#pragma once
// The JSON lines that describe scenes to the debugger and to recordings (docs/recording_format.md):
// scenes and actors once, then frames. One StreamState per consumer (a file, the debug server)
// remembers what that consumer has been told.

#include <map>
#include <set>
#include <string>

#include "scene/scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// What one consumer has been told so far.
struct StreamState {
  std::map<SceneHandle, double> last_frame;           // per scene: time of its last frame
  std::map<SceneHandle, std::set<ActorHandle>> seen;  // per scene: actors already described
  std::map<SceneHandle, std::set<std::string>> signal_kinds;  // per scene: signals whose kind was sent
};

// The recording's first line.
std::string header_line(double frame_interval);

// Appends to `out` the lines a consumer needs for a frame of scene `s` now: the scene's and new
// actors' descriptions, `destroy` lines for actors gone, then the frame; each line ends in '\n'.
void append_frame_lines(const SceneData& s, StreamState& state, std::string& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
