#pragma once
/// @file debug_server.h
/// The scene debugger's server: HTTP and WebSocket on 127.0.0.1, on its own thread. It serves
/// the debugger page (superdex_debugger/, built) and streams the scene to it
/// (docs/debugger_protocol.md); the page pauses, steps, plays and restores the simulation.
/// In replay mode it streams a recording file instead (docs/recording_format.md).
///
/// Security: every URL carries a random per-session token; requests from other origins,
/// paths outside the UI's folder and malformed WebSocket messages are refused or dropped.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace superdex::physics {

/// Which way the page draws "up": FLU (x forward, y left, z up; the engine's frame) or RUB
/// (x right, y up, z back).
enum class CoordinateAxes { FLU, RUB };

/// Playback state chosen from the page.
struct DebugPlayState {
  bool paused = false;      ///< scene.step blocks until play or step
  bool real_time = true;    ///< no faster than the wall clock (else as fast as possible)
};

/// The process's one debug server (see get_debug_server()).
class DebugServer {
 public:
  /// Starts serving on 127.0.0.1:`port` (0: a free port) in live mode, on a new thread; returns
  /// the port. Throws superdex::Error when the port cannot be bound, the UI is not built, or the
  /// server already runs.
  int start(int port = 0);
  /// Serves the page in replay mode: every connection receives the recording at `path`.
  /// Throws superdex::Error when the file cannot be read or the server already runs.
  int start_replay(const std::string& path, int port = 0);
  /// Closes every connection and the listening socket; releases a paused simulation.
  void stop();
  bool has_started() const;
  /// Whether a page is connected over the WebSocket.
  bool has_connection() const;
  /// The listening port; 0 when not started.
  int port() const;
  /// The page's URL, token included ("" when not started).
  std::string url() const;
  /// The folder of the built UI (index.html and its assets); default: the repository's
  /// superdex_debugger/dist. Throws superdex::Error while the server runs.
  void set_ui_directory(const std::string& path);
  std::string ui_directory() const;
  /// The axes the page uses; sent to pages that connect afterwards.
  void set_coordinate_axes(CoordinateAxes axes);
  CoordinateAxes coordinate_axes() const;
  /// The playback state chosen from the page (live mode).
  DebugPlayState play_state() const;
  /// Blocks until a page is connected or `timeout_seconds` passed; true when connected.
  bool wait_for_connection(double timeout_seconds) const;

  // ---- the simulation side (called by Scene::step on the stepping thread) -------------------

  /// Blocks while the page holds the simulation paused (until play, step or stop). When the page
  /// asked to restore since `restores_seen`, calls `restore` (also while paused) and updates it.
  void gate_step(std::uint64_t& restores_seen, const std::function<void()>& restore);
  /// Sleeps so that simulated time `t` (s) of the scene keyed `scene_key` does not run ahead of
  /// the wall clock in real-time play.
  void pace(std::uint64_t scene_key, double t);
  /// True when a frame should be built now: a page is connected, 1/60 s of wall time passed
  /// since the last frame, and the pages have taken the previous frames.
  bool wants_frame() const;
  /// True once after a page connected: every scene and actor must be described again. Frames
  /// broadcast before the next call are not sent to that page.
  bool take_resync();
  /// Sends JSON lines (one or more, '\n' separated) to every connected page; `build_seconds` is
  /// the stepping thread's time spent making them. Frames are spaced so that building them
  /// takes at most 3 % of the stepping thread's time.
  void broadcast(std::string lines, double build_seconds = 0);
  /// Reports the latest simulated time and step count (shown by the page's status).
  void report_progress(double t, std::int64_t step);

  DebugServer();
  ~DebugServer();
  DebugServer(const DebugServer&) = delete;
  DebugServer& operator=(const DebugServer&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The process's debug server (created on first use, stopped at exit).
DebugServer& get_debug_server();

}  // namespace superdex::physics
