#pragma once

// What every fuzz target shares: the input bytes as a file (pixelcloth's readers take paths, as the CLI gives them),
// and the one outcome of bad input that is not a finding, core::InputError (exit 2 in the CLI). Anything else that
// leaves a reader -- another exception, a crash, a sanitizer report, a leak, a hang -- is a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "pixelcloth/core/error.h"

namespace pixelcloth::fuzz {

/// This process's scratch folder: /dev/shm when there is one (the inputs never reach the disk), else the temp dir.
/// Removed at a normal exit.
inline const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    std::error_code ec;
    const std::filesystem::path base =
        std::filesystem::is_directory("/dev/shm", ec) ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
    std::filesystem::path d = base / ("pixelcloth-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(scratch(), ignored);
    });
    return d;
  }();
  return dir;
}

/// Writes the input to scratch()/name and returns that path.
inline std::filesystem::path writeInput(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = scratch() / name;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// The folder a target writes its seed inputs to, through pixelcloth's own writers, when PIXELCLOTH_FUZZ_SEED_OUT names
/// one (tests/fuzz/README.md: how the corpus was made); null otherwise.
inline const char* seedOut() { return std::getenv("PIXELCLOTH_FUZZ_SEED_OUT"); }

/// A JSON array nested `levels` deep, for seeds beyond core::parseJson's bound of 64 levels (a depth bomb): the fuzzer
/// starts from them and mutates around the depth check (docs/reliability.md, finding 15).
inline std::string deepNesting(int levels) { return std::string(levels, '[') + std::string(levels, ']'); }

/// Runs `read`, accepting the documented refusal of bad input.
template <typename F>
int guarded(F&& read) {
  try {
    read();
  } catch (const core::InputError&) {
  }
  return 0;
}

}  // namespace pixelcloth::fuzz
