#include "pixelcloth/core/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>

#include "pixelcloth/core/log.h"

namespace pixelcloth::core {

namespace {
std::mutex gProgressMutex;
}

std::string formatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  auto total = static_cast<long long>(std::llround(seconds));
  char buffer[32];
  if (total >= 3600) {
    std::snprintf(buffer, sizeof(buffer), "%lld:%02lld:%02lld", total / 3600, (total / 60) % 60, total % 60);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%lld:%02lld", total / 60, total % 60);
  }
  return buffer;
}

Progress::Progress(std::string label, std::int64_t total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()), lastDraw_(start_) {}

Progress::~Progress() {
  if (!finished_) finish();
}

void Progress::advance(std::int64_t count) {
  std::lock_guard<std::mutex> lock(gProgressMutex);
  done_ += count;
  auto now = std::chrono::steady_clock::now();
  // Redraw in place 5 times a second on a terminal; in a log file, one line every 2 s.
  auto interval = std::chrono::milliseconds(::isatty(STDERR_FILENO) ? 200 : 2000);
  if (now - lastDraw_ > interval) {
    lastDraw_ = now;
    draw(false);
  }
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(gProgressMutex);
  if (finished_) return;
  finished_ = true;
  draw(true);
}

std::string Progress::line() const {
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  double rate = elapsed > 0 ? done_ / elapsed : 0.0;
  char buffer[256];
  if (total_ > 0) {
    double eta = rate > 0 ? (total_ - done_) / rate : -1.0;
    std::snprintf(buffer, sizeof(buffer), "%s  %lld/%lld  %3d%%  %.1f/s  ETA %s", label_.c_str(),
                  static_cast<long long>(done_), static_cast<long long>(total_),
                  static_cast<int>(100.0 * done_ / total_), rate, formatDuration(eta).c_str());
  } else {
    std::snprintf(buffer, sizeof(buffer), "%s  %lld  %.1f/s", label_.c_str(), static_cast<long long>(done_), rate);
  }
  return buffer;
}

void Progress::draw(bool final) {
  if (logLevel() < LogLevel::Info) return;
  std::string text = line();
  if (final) {
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    text += "  done in " + formatDuration(elapsed);
  }
  // On a terminal, redraw in place; in a log file, print whole lines only.
  if (::isatty(STDERR_FILENO)) {
    std::cerr << '\r' << text << "\033[K" << (final ? "\n" : "") << std::flush;
  } else {
    std::cerr << text << '\n';
  }
}

}  // namespace pixelcloth::core
