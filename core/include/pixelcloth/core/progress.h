#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace pixelcloth::core {

/// A progress line on stderr: "label  120/500  24%  38.2/s  ETA 0:10". Redrawn at most every 0.2 s,
/// finished with a summary line. Silent below the Info log level (`--quiet`). Thread-safe `advance`.
class Progress {
 public:
  Progress(std::string label, std::int64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Marks `count` more items as done.
  void advance(std::int64_t count = 1);
  /// Prints the final line (called by the destructor if not called before).
  void finish();

  /// The text of the current progress line (also used by tests).
  std::string line() const;

 private:
  void draw(bool final);
  std::string label_;
  std::int64_t total_;
  std::int64_t done_ = 0;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
};

/// Formats seconds as h:mm:ss or m:ss.
std::string formatDuration(double seconds);

}  // namespace pixelcloth::core
