#pragma once
// One logger for the library: the host application may route messages anywhere.
#include <functional>
#include <string_view>

namespace facet {

enum class LogLevel { debug, info, warning, error };

using LogSink = std::function<void(LogLevel, std::string_view)>;

// Replaces the process-wide sink (default: warnings and errors to stderr,
// everything when FACET_LOG=debug). Thread-safe.
void set_log_sink(LogSink sink);
void log(LogLevel level, std::string_view message);

}  // namespace facet
