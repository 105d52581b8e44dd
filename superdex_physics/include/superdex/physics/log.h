#pragma once
/// @file log.h
/// The engine's log: every message goes to one channel, is dropped when its channel is
/// disabled, and otherwise reaches the log callback (by default: Verbose and Info to stdout,
/// Warning and Error to stderr). Thread-safe; the callback may be called from any thread that
/// logs, one call at a time.

#include <functional>
#include <string>
#include <string_view>

namespace superdex::physics {

enum class LogChannel { Verbose, Info, Warning, Error };

/// "Verbose", "Info", "Warning" or "Error".
const char* log_channel_name(LogChannel channel);

/// Receives each message that passes its channel's filter: the text ends with a newline;
/// `file` and `line` name where it was logged from (empty and 0 when unknown).
using LogCallback = std::function<void(LogChannel channel, std::string_view message, std::string_view file, int line)>;

/// Replaces the callback; an empty one restores the default printer.
void set_log_callback(LogCallback callback);
/// Verbose is disabled by default, the other channels enabled.
void enable_log_channel(LogChannel channel, bool enable);
bool is_log_channel_enabled(LogChannel channel);
/// Logs `message` (a newline is appended when it has none).
void log(LogChannel channel, std::string_view message, std::string_view file = {}, int line = 0);

inline void log_warning(std::string_view message) { log(LogChannel::Warning, message); }
inline void log_info(std::string_view message) { log(LogChannel::Info, message); }

}  // namespace superdex::physics
