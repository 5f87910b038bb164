#include "pixelcloth/core/error.h"

#include <filesystem>

namespace pixelcloth::core::detail {

namespace {
std::string location(const char* file, int line) {
  return std::filesystem::path(file).filename().string() + ":" + std::to_string(line);
}
}  // namespace

void throwInputError(const std::string& message, const char* file, int line) {
  throw InputError(message, location(file, line));
}

void throwInternalError(const std::string& message, const char* file, int line) {
  throw InternalError(message, location(file, line));
}

}  // namespace pixelcloth::core::detail
