// The debug server's stepping-thread side against stop(): a thread that makes every call a step
// makes (progress, pacing, the gate, frames) while the server is started and stopped again and
// again, with a page attached over the WebSocket, must never touch a server that stop() let go.

#include <gtest/gtest.h>

#include <atomic>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>

#include <unistd.h>

#include "superdex/physics/debug_server.h"

namespace {

namespace asio = boost::asio;
namespace websocket = boost::beast::websocket;
using superdex::physics::DebugServer;
using superdex::physics::get_debug_server;

// A folder with the page's index.html, removed at the end.
struct UiFolder {
  std::filesystem::path path = std::filesystem::temp_directory_path() / ("superdex_ui_" + std::to_string(::getpid()));
  UiFolder() {
    std::filesystem::create_directories(path);
    std::ofstream(path / "index.html") << "<!doctype html><title>debugger</title>";
  }
  ~UiFolder() { std::filesystem::remove_all(path); }
};

// Attaches a page over the WebSocket (the URL's token, a local host); false if refused.
bool attach_page(const DebugServer& server, asio::io_context& io, websocket::stream<asio::ip::tcp::socket>& ws) {
  const std::string url = server.url();  // http://127.0.0.1:PORT/TOKEN/
  const std::string path = url.substr(url.find('/', 7)) + "ws";
  boost::system::error_code ec;
  asio::ip::tcp::resolver resolver(io);
  asio::connect(ws.next_layer(), resolver.resolve("127.0.0.1", std::to_string(server.port()), ec), ec);
  if (!ec) ws.handshake("127.0.0.1:" + std::to_string(server.port()), path, ec);
  return !ec;
}

TEST(DebugServer, StopWhileAStepIsInsideTheServerIsSafe) {
  UiFolder ui;
  DebugServer& server = get_debug_server();
  server.set_ui_directory(ui.path.string());

  // the stepping thread: what Scene::step asks of the server, as fast as it can
  std::atomic<bool> stepping{true};
  std::atomic<long> steps{0};
  std::thread stepper([&] {
    std::uint64_t restores_seen = 0;
    double t = 0;
    while (stepping) {
      server.gate_step(restores_seen, [] {});
      t += 1e-3;
      (void)server.has_started();
      (void)server.url();
      server.report_progress(t, steps);
      server.pace(1, t);
      if (server.has_connection() && server.wants_frame()) {
        (void)server.take_resync();
        server.broadcast("{\"type\":\"frame\"}\n", 1e-6);
      }
      ++steps;
    }
  });

  std::mt19937 rng(3);
  int attached = 0;
  for (int cycle = 0; cycle < 150; ++cycle) {
    server.start();
    asio::io_context io;
    websocket::stream<asio::ip::tcp::socket> ws(io);
    std::thread reader;
    if (attach_page(server, io, ws)) {
      ++attached;
      // the page reads its frames, and answers the server's close
      reader = std::thread([&ws] {
        boost::beast::flat_buffer buffer;
        boost::system::error_code ec;
        while (!ec) ws.read(buffer, ec), buffer.clear();
      });
    }
    // stop at a random moment of the steps: pacing, sending a frame, reporting progress
    std::this_thread::sleep_for(std::chrono::microseconds(rng() % 3000));
    server.stop();
    if (reader.joinable()) reader.join();
    EXPECT_FALSE(server.has_started());
    EXPECT_EQ(server.url(), "");
  }
  EXPECT_GT(attached, 140);
  // the stepping thread is not held by a server that is gone
  const long before = steps;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (steps < before + 1000 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
  EXPECT_GE(steps, before + 1000);
  stepping = false;
  stepper.join();
}

}  // namespace
