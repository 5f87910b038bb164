#pragma once

#include <sstream>
#include <string>

namespace pixelcloth::core {

/// Quiet: nothing; Warning: only what loses or drops data; Info: also progress and information (the default).
enum class LogLevel { Quiet = 0, Warning = 1, Info = 2, Debug = 3 };

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

/// Streams a warning to stderr, prefixed "warning: ": for what loses or drops data (samples not saved, attributes a
/// format cannot hold). Shown unless the level is Quiet, so `--quiet` keeps it.
#define PIXELCLOTH_WARN(message)                                                                        \
  do {                                                                                                  \
    if (::pixelcloth::core::logLevel() >= ::pixelcloth::core::LogLevel::Warning) {                      \
      std::ostringstream pixelcloth_log_stream_;                                                        \
      pixelcloth_log_stream_ << "warning: " << message;                                                 \
      ::pixelcloth::core::logLine(::pixelcloth::core::LogLevel::Warning, pixelcloth_log_stream_.str()); \
    }                                                                                                   \
  } while (false)
