// The debug server (superdex/physics/debug_server.h): its thread, the play state the pages set,
// and the stepping thread's side (gating, real-time pacing, frames).

#include "superdex/physics/debug_server.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <atomic>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "http_session.h"
#include "recording_reader.h"
#include "request_policy.h"
#include "server_core.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
#include "websocket_session.h"

#ifndef SUPERDEX_DEBUGGER_UI_DIR
#define SUPERDEX_DEBUGGER_UI_DIR ""
#endif

namespace superdex::physics {

using debug::ServerCore;
using debug::WebSocketSession;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

namespace debug {

std::string ServerCore::session_message() const {
  return json{{"type", "session"}, {"mode", replay ? "replay" : "live"}, {"version", 1},
              {"axes", axes == CoordinateAxes::FLU ? "FLU" : "RUB"}, {"source", replay_source}}
      .dump();
}

std::string ServerCore::status_message() const {
  std::lock_guard lock(control_mutex);
  return json{{"type", "status"}, {"state", play.paused ? "paused" : "playing"}, {"speed", play.real_time ? "realtime" : "fast"},
              {"t", latest_time.load()}, {"step", latest_step.load()}}
      .dump();
}

void ServerCore::on_open(const std::shared_ptr<WebSocketSession>& session) {
  sessions.insert(session);
  // a page that attaches is described from scratch, and takes no frame built before that
  if (!replay) session->set_generation(++generation);
  ++connections;
  if (replay) return;
  // and it sees the simulation play in real time
  {
    std::lock_guard lock(control_mutex);
    play = DebugPlayState{};
    ++play_epoch;
  }
  control_changed.notify_all();
  session->send(std::make_shared<const std::string>(status_message()));
}

void ServerCore::on_close(const std::shared_ptr<WebSocketSession>& session) {
  if (!sessions.erase(session)) return;
  --connections;
  update_backlog();
  if (connections > 0 || replay) return;
  // nobody is watching: never leave the simulation paused
  {
    std::lock_guard lock(control_mutex);
    play = DebugPlayState{};
    ++play_epoch;
  }
  control_changed.notify_all();
}

void ServerCore::on_message(WebSocketSession& from, const std::string& text) {
  if (replay) return;
  const json message = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!message.is_object()) return;
  if (message.value("type", json()) == "ack") {
    from.acknowledge();
    update_backlog();
    return;
  }
  if (message.value("type", json()) != "control") return;
  const json action_value = message.value("action", json());
  if (!action_value.is_string()) return;
  const std::string action = action_value.get<std::string>();
  {
    std::lock_guard lock(control_mutex);
    // playing drops a single step still pending: it would run on the next pause
    if (action == "pause") play.paused = true;
    else if (action == "play") play = {false, true}, step_tokens = 0;
    else if (action == "fast") play = {false, false}, step_tokens = 0;
    else if (action == "step") {
      play.paused = true;
      step_tokens = 1;
    } else if (action == "restore") {
      play.paused = true;
      step_tokens = 0;
      ++restores;
    } else return;
    ++play_epoch;
  }
  control_changed.notify_all();
  send_all(std::make_shared<const std::string>(status_message()));
}

void ServerCore::send_all(const std::shared_ptr<const std::string>& message) {
  for (const auto& s : sessions) s->send(message);
  update_backlog();
}

void ServerCore::send_frame_all(const std::shared_ptr<const std::string>& message, std::uint64_t generation) {
  for (const auto& s : sessions) s->send_frame(message, generation);
  update_backlog();
}

void ServerCore::update_backlog() {
  int worst = 0;
  for (const auto& s : sessions) worst = std::max(worst, s->backlog());
  max_backlog = worst;
}

}  // namespace debug

struct DebugServer::Impl {
  // The running server, or none. Calls from the stepping thread hold their own reference for
  // as long as they use it, so stop() never frees a core that a step is still inside.
  std::shared_ptr<ServerCore> core;
  mutable std::mutex core_mutex;  // guards `core` itself (not what it points to)
  std::atomic<bool> live{false};  // whether `core` is set: a step with no server takes no lock
  std::mutex lifecycle_mutex;     // start and stop, one at a time
  // the server thread's objects (touched by start/stop and the server thread only)
  std::unique_ptr<tcp::acceptor> acceptor;
  std::unique_ptr<asio::steady_timer> status_timer;
  std::thread thread;
  int quiet_ticks = 0;  // status ticks without progress (server thread)
  std::string ui_dir = SUPERDEX_DEBUGGER_UI_DIR;
  std::atomic<CoordinateAxes> axes{CoordinateAxes::FLU};

  std::shared_ptr<ServerCore> current() const {
    if (!live.load(std::memory_order_acquire)) return nullptr;
    std::lock_guard lock(core_mutex);
    return core;
  }

  void accept(ServerCore& c) {
    acceptor->async_accept([this, &c](boost::system::error_code ec, tcp::socket socket) {
      if (ec) return;  // closed by stop()
      std::make_shared<debug::HttpSession>(std::move(socket), c)->run();
      accept(c);
    });
  }

  // status at least once a second (and when time moved), on the server thread
  void tick_status(ServerCore& c, double last_t) {
    status_timer->expires_after(std::chrono::milliseconds(250));
    status_timer->async_wait([this, &c, last_t](boost::system::error_code ec) {
      if (ec) return;
      const double t = c.latest_time.load();
      if (c.connections > 0 && !c.replay && (t != last_t || ++quiet_ticks >= 4)) {
        quiet_ticks = 0;
        c.send_all(std::make_shared<const std::string>(c.status_message()));
      }
      tick_status(c, t);
    });
  }

  int launch(int port, std::shared_ptr<ServerCore> c) {
    std::lock_guard life(lifecycle_mutex);
    if (const auto running = current()) throw Error("debug server: already started on port " + std::to_string(running->port));
    if (port < 0 || port > 65535) throw Error("debug server: port must be in 0..65535, got " + std::to_string(port));
    if (!is_existing_file(std::filesystem::path(ui_dir) / "index.html"))
      throw Error("debug server: the debugger UI is not built (no index.html in '" + ui_dir +
                  "'); build it with `npm run build` in superdex_debugger/ or set the UI directory");
    c->ui_dir = ui_dir;
    c->axes = axes.load();
    c->token = debug::random_token();
    auto new_acceptor = std::make_unique<tcp::acceptor>(c->io);
    boost::system::error_code ec;
    const tcp::endpoint endpoint(asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port));
    new_acceptor->open(endpoint.protocol(), ec);
    if (!ec) new_acceptor->set_option(asio::socket_base::reuse_address(true), ec);
    if (!ec) new_acceptor->bind(endpoint, ec);
    if (!ec) new_acceptor->listen(asio::socket_base::max_listen_connections, ec);
    if (ec) throw Error("debug server: cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + ec.message());
    c->port = new_acceptor->local_endpoint().port();
    c->running = true;
    acceptor = std::move(new_acceptor);
    status_timer = std::make_unique<asio::steady_timer>(c->io);
    accept(*c);
    tick_status(*c, -1);
    thread = std::thread([&io = c->io] { io.run(); });
    const int bound = c->port;
    {
      std::lock_guard lock(core_mutex);
      core = std::move(c);
    }
    live.store(true, std::memory_order_release);
    return bound;
  }

  void shutdown() {
    std::lock_guard life(lifecycle_mutex);
    // from here on the stepping thread sees no server; a step inside a call keeps its reference
    std::shared_ptr<ServerCore> c;
    {
      std::lock_guard lock(core_mutex);
      c = std::move(core);
      live.store(false, std::memory_order_release);
    }
    if (!c) return;
    {
      std::lock_guard lock(c->control_mutex);
      c->running = false;
      c->play = DebugPlayState{};
    }
    c->control_changed.notify_all();
    asio::post(c->io, [this, c = c.get()] {
      boost::system::error_code ignored;
      acceptor->close(ignored);
      status_timer->cancel();
      for (auto s : std::set(c->sessions)) s->close();
    });
    // pages get up to 200 ms to complete the close; then the loop is stopped
    auto guard = std::thread([&c = *c] {
      const auto deadline = Clock::now() + std::chrono::milliseconds(200);
      while (c.connections > 0 && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      c.io.stop();
    });
    thread.join();
    guard.join();
    c->sessions.clear();
    status_timer.reset();
    acceptor.reset();
  }
};

DebugServer::DebugServer() : impl_(std::make_unique<Impl>()) {}

DebugServer::~DebugServer() { impl_->shutdown(); }

int DebugServer::start(int port) { return impl_->launch(port, std::make_shared<ServerCore>()); }

int DebugServer::start_replay(const std::string& path, int port) {
  debug::RecordingLines recording = debug::read_recording(path);
  auto core = std::make_shared<ServerCore>();
  core->replay = true;
  core->replay_source = std::filesystem::path(path).filename().string();
  core->replay_lines = std::make_shared<std::vector<std::string>>(std::move(recording.lines));
  core->replay_frames = recording.frames;
  return impl_->launch(port, std::move(core));
}

void DebugServer::stop() { impl_->shutdown(); }

bool DebugServer::has_started() const { return impl_->current() != nullptr; }

bool DebugServer::has_connection() const {
  const auto core = impl_->current();
  return core && core->connections > 0;
}

int DebugServer::port() const {
  const auto core = impl_->current();
  return core ? core->port : 0;
}

std::string DebugServer::url() const {
  const auto core = impl_->current();
  if (!core) return {};
  return "http://127.0.0.1:" + std::to_string(core->port) + "/" + core->token + "/";
}

void DebugServer::set_ui_directory(const std::string& path) {
  std::lock_guard life(impl_->lifecycle_mutex);
  if (impl_->current()) throw Error("debug server: set the UI directory before start()");
  impl_->ui_dir = path;
}

std::string DebugServer::ui_directory() const { return impl_->ui_dir; }

void DebugServer::set_coordinate_axes(CoordinateAxes axes) {
  impl_->axes = axes;
  if (const auto core = impl_->current()) core->axes = axes;
}

CoordinateAxes DebugServer::coordinate_axes() const { return impl_->axes; }

DebugPlayState DebugServer::play_state() const {
  const auto core = impl_->current();
  if (!core) return {};
  std::lock_guard lock(core->control_mutex);
  return core->play;
}

bool DebugServer::wait_for_connection(double timeout_seconds) const {
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_seconds));
  while (!has_connection()) {
    if (!has_started() || Clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

void DebugServer::gate_step(std::uint64_t& restores_seen, const std::function<void()>& restore) {
  const auto core = impl_->current();
  if (!core || core->replay) return;
  std::unique_lock lock(core->control_mutex);
  for (;;) {
    if (core->restores != restores_seen) {
      restores_seen = core->restores;
      lock.unlock();
      restore();
      lock.lock();
      continue;
    }
    if (!core->running || !core->play.paused) return;
    if (core->step_tokens > 0) {
      --core->step_tokens;
      return;
    }
    core->control_changed.wait(lock);
  }
}

void DebugServer::pace(std::uint64_t scene_key, double t) {
  const auto core = impl_->current();
  if (!core || core->replay || core->connections == 0) return;
  std::unique_lock lock(core->control_mutex);
  if (core->play.paused || !core->play.real_time) return;
  auto& anchor = core->anchors[scene_key];
  const auto now = Clock::now();
  const auto due = anchor.wall + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(t - anchor.sim));
  // a new play state, or a simulation slower than the wall clock: start pacing from here
  if (anchor.epoch != core->play_epoch || anchor.wall == Clock::time_point{} || now - due > std::chrono::milliseconds(250)) {
    anchor = {now, t, core->play_epoch};
    return;
  }
  const std::uint64_t epoch = core->play_epoch;
  core->control_changed.wait_until(lock, due, [&] { return core->play_epoch != epoch || !core->running; });
}

bool DebugServer::wants_frame() const {
  const auto core = impl_->current();
  if (!core || core->replay || core->connections == 0) return false;
  if (core->generation != core->described_generation) return true;
  const auto since = std::chrono::duration<double>(Clock::now() - core->last_frame).count();
  // at most 60 frames per second, and frames may cost the simulation at most 3 % of its time
  const double spacing = std::max(1.0 / 60, core->frame_cost / 0.03);
  // a page that stopped acknowledging still gets a frame now and then
  return since >= spacing && (core->max_backlog < 2 || since >= std::max(0.5, spacing));
}

bool DebugServer::take_resync() {
  const auto core = impl_->current();
  if (!core) return false;
  const std::uint64_t generation = core->generation;
  return core->described_generation.exchange(generation) != generation;
}

void DebugServer::broadcast(std::string lines, double build_seconds) {
  const auto core = impl_->current();
  if (!core || core->connections == 0) return;
  core->last_frame = Clock::now();
  core->frame_cost = core->frame_cost == 0 ? build_seconds : 0.8 * core->frame_cost + 0.2 * build_seconds;
  // counted now so that wants_frame() sees the backlog before the server thread does
  ++core->max_backlog;
  auto message = std::make_shared<const std::string>(std::move(lines));
  // run by the server thread, which stop() joins before it lets go of the core
  asio::post(core->io, [c = core.get(), message, generation = core->described_generation.load()] {
    c->send_frame_all(message, generation);
  });
}

void DebugServer::report_progress(double t, std::int64_t step) {
  const auto core = impl_->current();
  if (!core) return;
  core->latest_time = t;
  core->latest_step = step;
}

DebugServer& get_debug_server() {
  static DebugServer server;
  return server;
}

}  // namespace superdex::physics
