#include "pixelcloth/core/error.h"

#include <filesystem>

namespace pixelcloth::core::detail {

void throwInputError(const std::string& message, const char* file, int line) {
  throw InputError(message, std::filesystem::path(file).filename().string() + ":" + std::to_string(line));
}

}  // namespace pixelcloth::core::detail
