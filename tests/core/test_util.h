#pragma once

#include <filesystem>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

namespace pixelcloth::testing {

/// An empty folder under the system's temporary directory, unique to the running test.
inline std::filesystem::path freshDir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "pixelcloth-tests" /
                              (std::string(info->test_suite_name()) + "." + info->name() + "." + name + "." +
                               std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Path of a file under tests/assets/.
inline std::filesystem::path asset(const std::string& name) { return std::filesystem::path(PIXELCLOTH_TEST_ASSETS) / name; }

}  // namespace pixelcloth::testing
