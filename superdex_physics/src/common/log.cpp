// The log channels, their filter and the callback (log.h).

#include "superdex/physics/log.h"

#include <array>
#include <atomic>
#include <cstdio>
#include <memory>
#include <mutex>

namespace superdex::physics {

namespace {

struct LogState {
  std::mutex mutex;
  // shared so that a call in progress keeps the callback it started with
  std::shared_ptr<const LogCallback> callback;
  std::array<std::atomic<bool>, 4> enabled{false, true, true, true};
};

LogState& state() {
  // never destroyed: threads may log while the process exits
  static LogState* s = new LogState();
  return *s;
}

void print_default(LogChannel channel, std::string_view message) {
  std::FILE* out = channel == LogChannel::Warning || channel == LogChannel::Error ? stderr : stdout;
  std::fprintf(out, "[superdex] %s: %.*s", log_channel_name(channel), static_cast<int>(message.size()), message.data());
  std::fflush(out);
}

}  // namespace

const char* log_channel_name(LogChannel channel) {
  switch (channel) {
    case LogChannel::Verbose: return "Verbose";
    case LogChannel::Info: return "Info";
    case LogChannel::Warning: return "Warning";
    case LogChannel::Error: return "Error";
  }
  return "?";
}

void set_log_callback(LogCallback callback) {
  LogState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  s.callback = callback ? std::make_shared<const LogCallback>(std::move(callback)) : nullptr;
}

void enable_log_channel(LogChannel channel, bool enable) { state().enabled[static_cast<int>(channel)] = enable; }

bool is_log_channel_enabled(LogChannel channel) { return state().enabled[static_cast<int>(channel)]; }

void log(LogChannel channel, std::string_view message, std::string_view file, int line) {
  LogState& s = state();
  if (!s.enabled[static_cast<int>(channel)]) return;
  std::string text(message);
  if (text.empty() || text.back() != '\n') text += '\n';
  std::shared_ptr<const LogCallback> callback;
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    callback = s.callback;
  }
  if (callback) (*callback)(channel, text, file, line);
  else print_default(channel, text);
}

}  // namespace superdex::physics
