#pragma once
// Reading a recording (docs/recording_format.md) for replay: every line is checked before the
// page sees it, so that a malformed file is refused with the line and field at fault instead of
// breaking the page halfway through a replay.

#include <cstddef>
#include <string>
#include <vector>

namespace superdex::physics::debug {

struct RecordingLines {
  std::vector<std::string> lines;  // the non-empty lines, in file order
  std::size_t frames = 0;          // how many are frames
};

/// Reads and checks the recording at `path`. Throws superdex::Error naming the file, the line
/// number, the field (`frame.t`) and what was expected. Line types and fields that this reader
/// does not know are accepted (the format says readers ignore them).
RecordingLines read_recording(const std::string& path);

}  // namespace superdex::physics::debug
