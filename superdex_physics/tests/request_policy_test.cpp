// The debug server's request checks (server/request_policy.h): token, Host, Origin, paths.

#include "request_policy.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace superdex::physics::debug {
namespace {

namespace fs = std::filesystem;
const std::string kToken = "0123456789abcdef0123456789abcdef";
constexpr int kPort = 8123;
const std::string kRoot = std::string("/").append(kToken);  // "/TOKEN"

RequestVerdict check(std::string_view target, std::string_view host = "127.0.0.1:8123", std::string_view origin = "") {
  return check_request(kToken, kPort, target, host, origin);
}

TEST(RequestPolicy, TheTokenMustLeadEveryPath) {
  EXPECT_EQ(check(kRoot + "/").status, 200);
  EXPECT_EQ(check(kRoot + "/assets/app.js?v=1").rest, "/assets/app.js");
  EXPECT_EQ(check(kRoot + "/ws").rest, "/ws");
  EXPECT_EQ(check(kRoot).status, 301);
  EXPECT_EQ(check("/").status, 403);
  EXPECT_EQ(check("/index.html").status, 403);
  EXPECT_EQ(check(kRoot + "x/").status, 403);
  EXPECT_EQ(check(std::string("/").append(kToken.substr(1)).append("/")).status, 403);
  EXPECT_EQ(check(std::string("/").append(32, 'f').append("/")).status, 403);
  EXPECT_EQ(check(std::string("//").append(kToken).append("/")).status, 403);
  EXPECT_EQ(check(std::string("/?").append(kToken)).status, 403);
}

TEST(RequestPolicy, OnlyLocalHostsAndOrigins) {
  const std::string page = kRoot + "/";
  EXPECT_EQ(check(page, "localhost:8123").status, 200);
  EXPECT_EQ(check(page, "evil.example:8123").status, 403);
  EXPECT_EQ(check(page, "127.0.0.1:8124").status, 403);
  EXPECT_EQ(check(page, "127.0.0.1").status, 403);
  EXPECT_EQ(check(page, "").status, 403);
  EXPECT_EQ(check(page, "127.0.0.1:8123", "http://127.0.0.1:8123").status, 200);
  EXPECT_EQ(check(page, "127.0.0.1:8123", "http://localhost:8123").status, 200);
  EXPECT_EQ(check(page, "127.0.0.1:8123", "http://evil.example").status, 403);
  EXPECT_EQ(check(page, "127.0.0.1:8123", "https://127.0.0.1:8123").status, 403);
  EXPECT_EQ(check(page, "127.0.0.1:8123", "http://127.0.0.1:81234").status, 403);
  EXPECT_EQ(check(page, "127.0.0.1:8123", "null").status, 403);
}

TEST(RequestPolicy, PercentDecoding) {
  EXPECT_EQ(percent_decode("a%2Fb%2e"), "a/b.");
  EXPECT_FALSE(percent_decode("%"));
  EXPECT_FALSE(percent_decode("%2"));
  EXPECT_FALSE(percent_decode("%zz"));
  EXPECT_FALSE(percent_decode("a%00b"));
  EXPECT_EQ(check(kRoot + "/%2e%2e/x").rest, "/../x");  // decoded here, refused by resolve_static_file
  EXPECT_EQ(check(kRoot + "/%zz").status, 404);
}

TEST(RequestPolicy, FilesOnlyFromInsideTheUiFolder) {
  const fs::path dir = fs::temp_directory_path() / ("superdex_ui_" + random_token());
  fs::create_directories(dir / "ui" / "assets");
  std::ofstream(dir / "ui" / "index.html") << "page";
  std::ofstream(dir / "ui" / "assets" / "app.js") << "js";
  std::ofstream(dir / "secret.txt") << "secret";
  fs::create_symlink(dir / "secret.txt", dir / "ui" / "out.txt");
  const fs::path ui = dir / "ui";
  EXPECT_EQ(resolve_static_file(ui, ""), fs::canonical(ui / "index.html"));
  EXPECT_EQ(resolve_static_file(ui, "/"), fs::canonical(ui / "index.html"));
  EXPECT_EQ(resolve_static_file(ui, "/assets/app.js"), fs::canonical(ui / "assets" / "app.js"));
  EXPECT_FALSE(resolve_static_file(ui, "/../secret.txt"));
  EXPECT_FALSE(resolve_static_file(ui, "/assets/../../secret.txt"));
  EXPECT_FALSE(resolve_static_file(ui, "/assets/../index.html"));  // no parent segments at all
  EXPECT_FALSE(resolve_static_file(ui, "/..\\secret.txt"));
  EXPECT_FALSE(resolve_static_file(ui, "/out.txt"));  // a link leading outside
  EXPECT_FALSE(resolve_static_file(ui, "/assets"));   // a folder
  EXPECT_FALSE(resolve_static_file(ui, "/missing.js"));
  EXPECT_FALSE(resolve_static_file(dir / "no_ui", "/"));
  EXPECT_EQ(mime_type("a.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(mime_type("a.bin"), "application/octet-stream");
  fs::remove_all(dir);
}

TEST(RequestPolicy, TokensAreRandomHex) {
  const std::string a = random_token(), b = random_token();
  EXPECT_EQ(a.size(), 32u);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
}

}  // namespace
}  // namespace superdex::physics::debug
