#include "pixelcloth/core/log.h"

#include <atomic>
#include <iostream>
#include <mutex>

namespace pixelcloth::core {

namespace {
std::atomic<int> gLevel{static_cast<int>(LogLevel::Info)};
std::mutex gStderrMutex;
}  // namespace

void setLogLevel(LogLevel level) { gLevel = static_cast<int>(level); }

LogLevel logLevel() { return static_cast<LogLevel>(gLevel.load()); }

void logLine(LogLevel level, const std::string& line) {
  if (static_cast<int>(level) > gLevel.load()) return;
  std::lock_guard<std::mutex> lock(gStderrMutex);
  std::cerr << line << '\n';
}

}  // namespace pixelcloth::core
