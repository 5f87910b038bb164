#pragma once

// numpy as an independent reader and writer of our files, in tests that skip themselves when it is missing.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace pixelcloth::testing {

// A Python interpreter that has numpy: `python3` on the PATH first, then Debian's own (a pyenv or venv python3 on the
// PATH may lack the python3-numpy package). Empty when there is none.
inline const std::string& numpyPython() {
  static const std::string found = [] {
    for (const char* python : {"python3", "/usr/bin/python3"}) {
      if (std::system((std::string(python) + " -c 'import numpy' >/dev/null 2>&1").c_str()) == 0) return python;
    }
    return "";
  }();
  return found;
}

// Runs a Python snippet and returns its stdout and stderr; `file` (a file or the test's folder) is sys.argv[1].
inline std::string runPython(const std::string& code, const std::filesystem::path& file) {
  const std::filesystem::path script =
      (std::filesystem::is_directory(file) ? file : file.parent_path()) / "check.py";  // inside the test's folder
  std::ofstream(script) << code;
  std::string command = numpyPython() + " '" + script.string() + "' '" + file.string() + "' 2>&1";
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return "popen failed";
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  ::pclose(pipe);
  return output;
}

}  // namespace pixelcloth::testing
