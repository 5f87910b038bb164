#pragma once

// Running the real `pixelcloth` executable from a test: its exit code, stdout and stderr, and the files it left.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace pixelcloth::testing {

namespace fs = std::filesystem;

/// What one command did: its exit code and what it printed.
struct CliRun {
  std::string command;
  int status = -1;  ///< WEXITSTATUS, or -1 when the command did not exit normally (signal)
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

inline std::ostream& operator<<(std::ostream& os, const CliRun& run) {
  return os << "\n$ " << run.command << "\nexit code " << run.status << "\n--- stdout ---\n"
            << run.out.substr(0, 4000) << "\n--- stderr ---\n"
            << run.err.substr(0, 4000) << "\n";
}

/// One shell word: `s` in single quotes.
inline std::string quote(const std::string& s) {
  std::string quoted = "'";
  for (char c : s) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

inline std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void writeFile(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

/// Runs a shell command line; stdout through a pipe, stderr through a temporary file.
inline CliRun capture(const std::string& command) {
  static int counter = 0;
  fs::path errFile = fs::temp_directory_path() /
                     ("pixelcloth-cli-test-stderr." + std::to_string(::getpid()) + "." + std::to_string(counter++));
  CliRun run;
  run.command = command;
  FILE* pipe = ::popen((command + " 2>" + quote(errFile.string())).c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) run.out.append(buffer, n);
  const int raw = ::pclose(pipe);
  run.status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.err = readFile(errFile);
  std::error_code ignored;
  fs::remove(errFile, ignored);
  return run;
}

/// Runs `pixelcloth ARGS...`, each argument passed as one word.
inline CliRun runPixelcloth(std::initializer_list<std::string> args) {
  std::string command = quote(PIXELCLOTH_BINARY);
  for (const std::string& arg : args) command += " " + quote(arg);
  return capture(command);
}

/// Exit code 2 and a message on stderr that contains every one of `mentions`; no internal error.
inline ::testing::AssertionResult refused(const CliRun& run, const std::vector<std::string>& mentions) {
  if (run.status != 2) return ::testing::AssertionFailure() << "expected exit code 2" << run;
  if (run.err.find("internal error") != std::string::npos)
    return ::testing::AssertionFailure() << "bad input reported as an internal error" << run;
  for (const std::string& mention : mentions) {
    if (run.err.find(mention) == std::string::npos)
      return ::testing::AssertionFailure() << "the message does not mention '" << mention << "'" << run;
  }
  return ::testing::AssertionSuccess();
}

/// Every regular file under `dir`, relative and sorted; empty when `dir` does not exist.
inline std::vector<std::string> filesUnder(const fs::path& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), dir).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace pixelcloth::testing
