#pragma once
// One logger for the library: the host application may route messages anywhere.
#include <functional>
#include <string_view>

namespace facet {

enum class LogLevel { debug, info, warning, error };

using LogSink = std::function<void(LogLevel, std::string_view)>;

// Replaces the process-wide sink (default: messages at or above the log level to
// stderr). Thread-safe.
void set_log_sink(LogSink sink);
// The least severe level the default sink prints (default: info; a sink set with
// set_log_sink receives every level). The library reads no environment variable: the
// programs map FACET_LOG=debug onto this. Thread-safe.
void set_log_level(LogLevel minimum);
LogLevel log_level();
void log(LogLevel level, std::string_view message);

}  // namespace facet
