#pragma once
// State shared by the debug server's thread (sessions) and the stepping thread (debug_server.cpp).

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "superdex/physics/debug_server.h"

namespace superdex::physics::debug {

class WebSocketSession;

struct ServerCore {
  boost::asio::io_context io;
  std::string token;
  int port = 0;
  std::filesystem::path ui_dir;
  std::atomic<CoordinateAxes> axes{CoordinateAxes::FLU};  // set from the user's thread
  // replay mode: the recording's lines, sent to every connection
  bool replay = false;
  std::string replay_source;
  std::shared_ptr<const std::vector<std::string>> replay_lines;
  std::size_t replay_frames = 0;

  // pages connected over the WebSocket (touched on the server thread only)
  std::set<std::shared_ptr<WebSocketSession>> sessions;
  std::atomic<int> connections{0};
  // the largest number of frames one page has not taken yet (see WebSocketSession::backlog)
  std::atomic<int> max_backlog{0};
  // goes up by one whenever a page attaches: the stepping thread then describes the scenes
  // again, and frames built before (on older descriptions) are not sent to that page
  std::atomic<std::uint64_t> generation{0};

  // play state set by the pages, waited on by the stepping thread
  mutable std::mutex control_mutex;
  std::condition_variable control_changed;
  DebugPlayState play;
  int step_tokens = 0;                 // steps allowed while paused
  std::uint64_t restores = 0;          // restore requests so far
  std::uint64_t play_epoch = 0;        // changes whenever play state changes (re-anchors pacing)
  bool running = false;

  // progress reported by the stepping thread, shown by the page
  std::atomic<double> latest_time{0};
  std::atomic<std::int64_t> latest_step{0};

  // the stepping thread's side of this server run (debug_server.cpp)
  std::chrono::steady_clock::time_point last_frame{};
  double frame_cost = 0;  // running mean of the seconds one frame costs the stepping thread
  // the generation the stepping thread's descriptions were sent for
  std::atomic<std::uint64_t> described_generation{0};
  // where real-time pacing of each scene started: wall clock, simulated time (s), play epoch
  struct PaceAnchor {
    std::chrono::steady_clock::time_point wall;
    double sim = 0;
    std::uint64_t epoch = 0;
  };
  std::map<std::uint64_t, PaceAnchor> anchors;  // by scene key, under control_mutex

  /// The `session` message for a new connection.
  std::string session_message() const;
  /// The `status` message of the current state.
  std::string status_message() const;
  /// A page connected (server thread).
  void on_open(const std::shared_ptr<WebSocketSession>& session);
  /// A page's connection ended (server thread).
  void on_close(const std::shared_ptr<WebSocketSession>& session);
  /// A text message from a page (server thread); malformed ones are dropped.
  void on_message(WebSocketSession& from, const std::string& text);
  /// Sends to every page (server thread).
  void send_all(const std::shared_ptr<const std::string>& message);
  /// Sends a frame built on descriptions of `generation` to every page that has them; each page
  /// acknowledges it (server thread).
  void send_frame_all(const std::shared_ptr<const std::string>& message, std::uint64_t generation);
  /// Recomputes max_backlog (server thread).
  void update_backlog();
};

}  // namespace superdex::physics::debug
