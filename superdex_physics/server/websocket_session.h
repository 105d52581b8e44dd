#pragma once
// One page's WebSocket connection to the debug server: a queue of outgoing messages written one
// at a time, and a read loop that hands text messages to the core (server thread only).

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <algorithm>
#include <deque>
#include <memory>
#include <string>

#include "server_core.h"

namespace superdex::physics::debug {

class WebSocketSession : public std::enable_shared_from_this<WebSocketSession> {
 public:
  WebSocketSession(boost::asio::ip::tcp::socket socket, ServerCore& core);
  /// Completes the upgrade of `request`, then starts reading.
  void accept(boost::beast::http::request<boost::beast::http::string_body> request);
  /// Queues a message (text).
  void send(std::shared_ptr<const std::string> message);
  /// Queues a frame message, counted until the page acknowledges it; dropped if it was built
  /// against descriptions older than this page (`generation` below the page's own).
  void send_frame(std::shared_ptr<const std::string> message, std::uint64_t generation);
  /// The description generation this page attached in (ServerCore::generation).
  void set_generation(std::uint64_t generation) { generation_ = generation; }
  /// The page has taken a frame (`{"type": "ack"}`).
  void acknowledge() { unacked_ = std::max(0, unacked_ - 1); }
  /// Frames the page has not taken yet, or messages not yet written, whichever is more.
  int backlog() const { return std::max(static_cast<int>(queue_.size()), unacked_); }
  /// Closes the connection.
  void close();

 private:
  void read();
  void write();
  void queue_replay_batch();
  void finish();

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  boost::beast::flat_buffer buffer_;
  std::deque<std::shared_ptr<const std::string>> queue_;
  ServerCore& core_;
  std::size_t replay_next_ = 0;  // next line of the recording to send (replay mode)
  bool open_ = false;
  int unacked_ = 0;  // frames sent and not acknowledged
  std::uint64_t generation_ = 0;  // frames of older generations lack this page's descriptions
};

}  // namespace superdex::physics::debug
