#pragma once

#include <sstream>
#include <string>

namespace pixelcloth::core {

enum class LogLevel { Quiet = 0, Info = 1, Debug = 2 };

/// Process-wide verbosity for messages on stderr (progress bars included). Default: Info.
void setLogLevel(LogLevel level);
LogLevel logLevel();

/// Writes one line to stderr when the current level is at least `level`.
void logLine(LogLevel level, const std::string& line);

}  // namespace pixelcloth::core

/// Streams an informational line to stderr: PIXELCLOTH_INFO("built " << n << " triangles");
#define PIXELCLOTH_INFO(message)                                                                     \
  do {                                                                                               \
    if (::pixelcloth::core::logLevel() >= ::pixelcloth::core::LogLevel::Info) {                      \
      std::ostringstream pixelcloth_log_stream_;                                                     \
      pixelcloth_log_stream_ << message;                                                             \
      ::pixelcloth::core::logLine(::pixelcloth::core::LogLevel::Info, pixelcloth_log_stream_.str()); \
    }                                                                                                \
  } while (false)
