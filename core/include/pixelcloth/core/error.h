#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace pixelcloth::core {

/// The user's input is wrong: a missing or malformed file, an out-of-range option, an unknown name.
/// `what()` is the message for the user (it names the file, the field and what was expected);
/// `where()` is the source location that raised it, for bug reports. The CLI maps it to exit code 2.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& message, std::string where = {})
      : std::runtime_error(message), where_(std::move(where)) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

/// Something that must not happen did: a solver that cannot factor a system it built, a broken invariant. It is a bug
/// in pixelcloth, not in the input. `what()` says so and names the source file and line; the CLI maps it to exit
/// code 1.
class InternalError : public std::logic_error {
 public:
  InternalError(const std::string& message, std::string where)
      : std::logic_error("internal error (a bug in pixelcloth, please report it) at " + where + ": " + message),
        where_(std::move(where)) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

namespace detail {
[[noreturn]] void throwInputError(const std::string& message, const char* file, int line);
[[noreturn]] void throwInternalError(const std::string& message, const char* file, int line);
}  // namespace detail

}  // namespace pixelcloth::core

/// Checks a condition on user input and throws `pixelcloth::core::InputError` when it fails.
/// Stays on in release builds. The message is streamed:
///   PIXELCLOTH_CHECK(f < nv, path << ": face " << i << " uses vertex " << f << ", but the file has " << nv);
#define PIXELCLOTH_CHECK(condition, message)                                                           \
  do {                                                                                                 \
    if (!(condition)) {                                                                                \
      std::ostringstream pixelcloth_check_stream_;                                                     \
      pixelcloth_check_stream_ << message;                                                             \
      ::pixelcloth::core::detail::throwInputError(pixelcloth_check_stream_.str(), __FILE__, __LINE__); \
    }                                                                                                  \
  } while (false)

/// Unconditional failure with the same message style as PIXELCLOTH_CHECK.
#define PIXELCLOTH_FAIL(message) PIXELCLOTH_CHECK(false, message)

/// Checks an invariant of pixelcloth's own code (not of user input) and throws `pixelcloth::core::InternalError` when
/// it fails. Stays on in release builds. The message is streamed, as in PIXELCLOTH_CHECK.
#define PIXELCLOTH_ASSERT(condition, message)                                                              \
  do {                                                                                                     \
    if (!(condition)) {                                                                                    \
      std::ostringstream pixelcloth_assert_stream_;                                                        \
      pixelcloth_assert_stream_ << "'" #condition "' failed: " << message;                                 \
      ::pixelcloth::core::detail::throwInternalError(pixelcloth_assert_stream_.str(), __FILE__, __LINE__); \
    }                                                                                                      \
  } while (false)
