// HTTP side of the debug server (http_session.h).

#include "http_session.h"

#include <chrono>
#include <fstream>
#include <sstream>

#include "request_policy.h"
#include "websocket_session.h"

namespace superdex::physics::debug {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;

HttpSession::HttpSession(boost::asio::ip::tcp::socket socket, ServerCore& core) : stream_(std::move(socket)), core_(core) {}

void HttpSession::run() { read(); }

void HttpSession::read() {
  request_ = {};
  stream_.expires_after(std::chrono::seconds(30));
  http::async_read(stream_, buffer_, request_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
    if (ec) {
      // malformed request, timeout or closed: drop the connection
      beast::error_code ignored;
      self->stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
      return;
    }
    self->handle();
  });
}

void HttpSession::handle() {
  const auto text_response = [this](http::status status, std::string body) {
    http::response<http::string_body> res{status, request_.version()};
    res.set(http::field::content_type, "text/plain; charset=utf-8");
    res.body() = std::move(body);
    return res;
  };
  const RequestVerdict verdict =
      check_request(core_.token, core_.port, request_.target(), request_[http::field::host], request_[http::field::origin]);
  if (verdict.status == 403) return respond(text_response(http::status::forbidden, "forbidden\n"));
  if (verdict.status == 404) return respond(text_response(http::status::not_found, "not found\n"));
  if (verdict.status == 301) {
    auto res = text_response(http::status::moved_permanently, "");
    res.set(http::field::location, "/" + core_.token + "/");
    return respond(std::move(res));
  }
  if (verdict.rest == "/ws") {
    if (!websocket::is_upgrade(request_)) return respond(text_response(http::status::bad_request, "WebSocket only\n"));
    auto session = std::make_shared<WebSocketSession>(stream_.release_socket(), core_);
    session->accept(std::move(request_));
    return;
  }
  if (request_.method() != http::verb::get && request_.method() != http::verb::head)
    return respond(text_response(http::status::method_not_allowed, "GET only\n"));
  const auto file = resolve_static_file(core_.ui_dir, verdict.rest);
  if (!file) return respond(text_response(http::status::not_found, "not found\n"));
  std::ifstream in(*file, std::ios::binary);
  std::ostringstream body;
  body << in.rdbuf();
  http::response<http::string_body> res{http::status::ok, request_.version()};
  res.set(http::field::content_type, mime_type(*file));
  res.set(http::field::cache_control, "no-store");
  res.set("X-Content-Type-Options", "nosniff");
  res.set("Referrer-Policy", "no-referrer");
  res.set("X-Frame-Options", "DENY");
  res.body() = request_.method() == http::verb::head ? std::string() : body.str();
  respond(std::move(res));
}

void HttpSession::respond(http::response<http::string_body> response) {
  response.set(http::field::server, "superdex-debugger");
  response.keep_alive(request_.keep_alive());
  response.prepare_payload();
  auto shared = std::make_shared<http::response<http::string_body>>(std::move(response));
  http::async_write(stream_, *shared, [self = shared_from_this(), shared](beast::error_code ec, std::size_t) {
    if (ec || shared->need_eof()) {
      beast::error_code ignored;
      self->stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_send, ignored);
      return;
    }
    self->read();
  });
}

}  // namespace superdex::physics::debug
