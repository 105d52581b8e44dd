// The step's hooks into the debug server (debug_link.h).

#include "output/debug_link.h"

#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>

#include "output/scene_messages.h"
#include "superdex/physics/debug_server.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

struct SceneLink {
  std::vector<std::uint8_t> initial_state;  // captured at its first step with the server running
  std::uint64_t restores_seen = 0;
};

struct LinkState {
  std::mutex mutex;
  std::string session_url;  // identifies the server run the states belong to
  // shared: a step holds its scene's link while another thread may start a new server run
  std::map<SceneHandle, std::shared_ptr<SceneLink>> scenes;
  StreamState stream;  // what the pages have been told
};

LinkState& link_state() {
  static LinkState state;
  return state;
}

// Sends the scene's frame (with any descriptions the pages lack) to the pages.
void send_frame(DebugServer& server, const SceneData& s, LinkState& state) {
  const auto start = std::chrono::steady_clock::now();
  if (server.take_resync()) state.stream = StreamState{};
  std::string lines;
  append_frame_lines(s, state.stream, lines);
  server.broadcast(std::move(lines), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

// Sends the scene's frame when the pages want one.
void send_wanted_frame(DebugServer& server, const SceneData& s) {
  if (!server.wants_frame()) return;
  LinkState& state = link_state();
  std::lock_guard lock(state.mutex);
  send_frame(server, s, state);
}

}  // namespace

void debug_before_step(Scene& scene) {
  DebugServer& server = get_debug_server();
  if (!server.has_started()) return;
  LinkState& state = link_state();
  std::shared_ptr<SceneLink> link;
  {
    std::lock_guard lock(state.mutex);
    // a new server run starts from the scenes' states at that time
    if (state.session_url != server.url()) {
      state.session_url = server.url();
      state.scenes.clear();
      state.stream = StreamState{};
    }
    auto& entry = state.scenes[scene.handle()];
    if (!entry) {
      entry = std::make_shared<SceneLink>();
      entry->initial_state = state_bytes(scene_data(scene.handle()));
    }
    link = entry;
  }
  server.gate_step(link->restores_seen, [&] {
    try {
      restore_state_bytes(scene_data(scene.handle()), link->initial_state);
    } catch (const Error& e) {
      // actors were added or removed since: the first state no longer fits this scene
      std::cerr << "superdex.debugger: cannot restore scene '" << scene.name() << "': " << e.what() << '\n';
      return;
    }
    const SceneData& s = scene_data(scene.handle());
    server.report_progress(s.time, s.step_count);
    std::lock_guard lock(state.mutex);
    send_frame(server, s, state);
  });
}

void debug_after_step(Scene& scene, const SceneData& s) {
  DebugServer& server = get_debug_server();
  if (!server.has_started()) return;
  server.report_progress(s.time, s.step_count);
  server.pace(s.handle, s.time);
  send_wanted_frame(server, s);
}

void debug_update(const SceneData& s) {
  DebugServer& server = get_debug_server();
  if (!server.has_started()) return;
  server.report_progress(s.time, s.step_count);
  send_wanted_frame(server, s);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
