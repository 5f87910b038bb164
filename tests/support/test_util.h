#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <string>

#include "pixelcloth/core/error.h"

namespace pixelcloth::testing {

/// An empty folder under the system's temporary directory, unique to the running test.
inline std::filesystem::path freshDir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "pixelcloth-tests" /
      (std::string(info->test_suite_name()) + "." + info->name() + "." + name + "." + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Path of a file under tests/assets/.
inline std::filesystem::path asset(const std::string& name) {
  return std::filesystem::path(PIXELCLOTH_TEST_ASSETS) / name;
}

/// The message of the `InputError` that `action` throws; records a test failure (and returns "") when it
/// throws nothing or something else.
inline std::string inputErrorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const pixelcloth::core::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return {};
}

}  // namespace pixelcloth::testing
