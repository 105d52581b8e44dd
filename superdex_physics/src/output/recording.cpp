// Recordings of simulation runs as JSON lines (superdex/physics/recording.h,
// docs/recording_format.md).

#include "superdex/physics/recording.h"

#include <cmath>
#include <fstream>
#include <map>
#include <mutex>

#include "output/recording_internal.h"
#include "output/scene_messages.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

struct Recording {
  std::ofstream out;
  std::string path;
  double frame_interval = 0;
  // per scene, the simulated time it has run since the recording started (the sum of its step
  // sizes: a restored state rewinds its clock, not this), and the most of them
  std::map<std::int64_t, double> simulated;
  double latest_time = 0;
  long long frames = 0;
  StreamState stream;
  std::map<std::int64_t, std::string> last_frame_line;  // per scene: its last frame's line
};

std::unique_ptr<Recording>& recording() {
  static std::unique_ptr<Recording> r;
  return r;
}

// Guards the running recording and its replacement: scenes stepped on other threads write to it
// while a script may stop it.
std::mutex& recording_mutex() {
  static std::mutex m;
  return m;
}

// The last line of `lines` (each line ends in '\n').
std::string last_line(const std::string& lines) {
  if (lines.size() < 2) return lines;
  const size_t start = lines.rfind('\n', lines.size() - 2);
  return start == std::string::npos ? lines : lines.substr(start + 1);
}

// Writes the scene's frame (with the descriptions it needs), unless `skip_repeat` and its frame
// line repeats the scene's last one (then it shows no change, nor a new actor, which would be in
// it).
void write_frame(Recording& r, const SceneData& s, bool skip_repeat) {
  std::string lines;
  append_frame_lines(s, r.stream, lines);
  std::string frame = last_line(lines);
  std::string& last = r.last_frame_line[s.handle];
  if (skip_repeat && frame == last) return;
  r.out << lines;
  r.frames += 1;
  last = std::move(frame);
}

}  // namespace

void start_recording(const std::string& path, double frame_interval) {
  std::lock_guard lock(recording_mutex());
  auto& r = recording();
  if (r) throw Error("start_recording: a recording to '" + r->path + "' is already running");
  if (!(frame_interval >= 0) || !std::isfinite(frame_interval))
    throw Error("start_recording: frame_interval must be >= 0 seconds");
  auto rec = std::make_unique<Recording>();
  rec->out.open(path, std::ios::out | std::ios::trunc);
  if (!rec->out) throw Error("start_recording: cannot write '" + path + "'");
  rec->path = path;
  rec->frame_interval = frame_interval;
  rec->out << header_line(frame_interval);
  r = std::move(rec);
}

void stop_recording() {
  std::lock_guard lock(recording_mutex());
  auto& r = recording();
  if (!r) return;
  r->out.flush();
  r.reset();
}

bool is_recording() {
  std::lock_guard lock(recording_mutex());
  return recording() != nullptr;
}

double recorded_time() {
  std::lock_guard lock(recording_mutex());
  return recording() ? recording()->latest_time : 0;
}

long long recorded_frames() {
  std::lock_guard lock(recording_mutex());
  return recording() ? recording()->frames : 0;
}

std::string recording_path() {
  std::lock_guard lock(recording_mutex());
  return recording() ? recording()->path : std::string();
}

void record_step(const SceneData& s) {
  std::lock_guard lock(recording_mutex());
  auto& r = recording();
  if (!r) return;
  double& simulated = r->simulated[s.handle];
  simulated += s.last_time_step;
  r->latest_time = std::max(r->latest_time, simulated);
  const auto& last = r->stream.last_frame;
  // a frame once frame_interval has passed since the last one, or at once when the clock went
  // back (a restored state: the replay starts a new epoch there); float builds step by float dt:
  // allow its rounding
  if (auto it = last.find(s.handle);
      it != last.end() && s.time >= it->second && s.time - it->second < r->frame_interval * (1 - 1e-6) - 1e-12)
    return;
  write_frame(*r, s, false);
}

void record_current_frame(const SceneData& s) {
  std::lock_guard lock(recording_mutex());
  auto& r = recording();
  if (!r) return;
  write_frame(*r, s, true);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
