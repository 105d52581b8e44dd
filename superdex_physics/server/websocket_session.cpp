// WebSocket side of the debug server (websocket_session.h).

#include "websocket_session.h"

namespace superdex::physics::debug {

namespace beast = boost::beast;
namespace websocket = beast::websocket;

namespace {
// replay batches: about this many bytes of recording lines per message
constexpr std::size_t kReplayBatchBytes = 512 * 1024;
// the largest message accepted from a page (control messages are tiny)
constexpr std::size_t kMaxIncomingBytes = 64 * 1024;
}  // namespace

WebSocketSession::WebSocketSession(boost::asio::ip::tcp::socket socket, ServerCore& core) : ws_(std::move(socket)), core_(core) {}

void WebSocketSession::accept(beast::http::request<beast::http::string_body> request) {
  beast::get_lowest_layer(ws_).expires_never();
  ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  ws_.read_message_max(kMaxIncomingBytes);
  ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
    if (ec) return;
    self->open_ = true;
    self->core_.on_open(self);
    self->send(std::make_shared<const std::string>(self->core_.session_message()));
    if (self->core_.replay) self->queue_replay_batch();
    self->read();
  });
}

void WebSocketSession::read() {
  ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
    if (ec) return self->finish();
    // binary frames are not part of the protocol: drop them
    if (self->ws_.got_text()) self->core_.on_message(*self, beast::buffers_to_string(self->buffer_.data()));
    self->buffer_.consume(self->buffer_.size());
    self->read();
  });
}

void WebSocketSession::send(std::shared_ptr<const std::string> message) {
  if (!open_) return;
  queue_.push_back(std::move(message));
  if (queue_.size() == 1) write();
}

void WebSocketSession::send_frame(std::shared_ptr<const std::string> message, std::uint64_t generation) {
  if (!open_ || generation < generation_) return;
  ++unacked_;
  send(std::move(message));
}

void WebSocketSession::write() {
  ws_.text(true);
  ws_.async_write(boost::asio::buffer(*queue_.front()), [self = shared_from_this()](beast::error_code ec, std::size_t) {
    if (ec) return self->finish();
    self->queue_.pop_front();
    // the next replay batch is produced only once the previous one is written
    if (self->queue_.empty() && self->core_.replay) self->queue_replay_batch();
    else if (!self->queue_.empty()) self->write();
    self->core_.update_backlog();
  });
}

void WebSocketSession::queue_replay_batch() {
  const auto& lines = *core_.replay_lines;
  if (replay_next_ > lines.size()) return;
  if (replay_next_ == lines.size()) {
    ++replay_next_;
    send(std::make_shared<const std::string>("{\"type\":\"end\",\"frames\":" + std::to_string(core_.replay_frames) + "}"));
    return;
  }
  auto batch = std::make_shared<std::string>();
  while (replay_next_ < lines.size() && batch->size() < kReplayBatchBytes) {
    *batch += lines[replay_next_++];
    *batch += '\n';
  }
  send(std::move(batch));
}

void WebSocketSession::close() {
  if (!open_) return;
  ws_.async_close(websocket::close_code::going_away, [self = shared_from_this()](beast::error_code) { self->finish(); });
}

void WebSocketSession::finish() {
  if (!open_) return;
  open_ = false;
  core_.on_close(shared_from_this());
}

}  // namespace superdex::physics::debug
