/// @file debugger_message_fuzzer.cpp
/// libFuzzer target for the debug server's handler of the pages' WebSocket text messages
/// (ServerCore::on_message, server/debug_server.cpp). The input is split at newlines into a
/// sequence of messages sent by one page, so that sequences (pause, step, ack, ...) are
/// reached too. Malformed messages must be dropped; after every message the play state must
/// still be one the stepping thread understands.

#include <boost/asio/ip/tcp.hpp>
#include <cstdlib>
#include <memory>
#include <string_view>

#include "server_core.h"
#include "websocket_session.h"

using superdex::physics::debug::ServerCore;
using superdex::physics::debug::WebSocketSession;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ServerCore core;
  // a page whose socket is not connected: what the server sends it is dropped (send() needs an
  // open session), what it receives goes through the real handler
  auto page = std::make_shared<WebSocketSession>(boost::asio::ip::tcp::socket(core.io), core);
  core.sessions.insert(page);
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  std::size_t start = 0;
  while (start <= input.size()) {
    const std::size_t end = std::min(input.find('\n', start), input.size());
    core.on_message(*page, std::string(input.substr(start, end - start)));
    start = end + 1;
    // the states the stepping thread can be left in: at most one pending single step, and a
    // backlog that never goes negative however many acks arrive
    if (core.step_tokens < 0 || core.step_tokens > 1 || core.max_backlog < 0 || page->backlog() < 0) std::abort();
    if (core.step_tokens == 1 && !core.play.paused) std::abort();
  }
  return 0;
}
