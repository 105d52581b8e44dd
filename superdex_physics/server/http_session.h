#pragma once
// One HTTP connection to the debug server: checks each request (request_policy.h), serves the
// UI's static files, and hands WebSocket upgrades of /TOKEN/ws to a WebSocketSession.

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <memory>

#include "server_core.h"

namespace superdex::physics::debug {

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket socket, ServerCore& core);
  void run();

 private:
  void read();
  void handle();
  void respond(boost::beast::http::response<boost::beast::http::string_body> response);

  boost::beast::tcp_stream stream_;
  boost::beast::flat_buffer buffer_;
  boost::beast::http::request<boost::beast::http::string_body> request_;
  ServerCore& core_;
};

}  // namespace superdex::physics::debug
