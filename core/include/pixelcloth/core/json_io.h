#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

/// The deepest nesting of arrays and objects a pixelcloth JSON reader accepts. Our files nest a few levels; a value
/// nested many thousands deep would overflow the stack when nlohmann copies or compares it.
constexpr int kMaxJsonDepth = 64;

/// Parses JSON `text`, refusing it before parsing when its arrays and objects nest deeper than kMaxJsonDepth. Throws
/// `InputError` starting with `context` (the file) for a syntax error, giving its line, column and byte offset
/// ("manifest.json: invalid JSON at line 3, column 7 (byte 25): ..."), or for the nesting.
nlohmann::json parseJson(const std::string& text, const std::string& context);

/// Reads and parses a JSON file (parseJson). Throws `InputError` naming the file for a missing file and, for a syntax
/// error, giving its line, column and byte offset ("manifest.json: invalid JSON at line 3, column 7 (byte 25): ...").
nlohmann::json readJson(const std::filesystem::path& path);

/// Writes `value` as JSON text (pretty-printed with `indent` spaces, compact when negative) followed by a newline,
/// atomically (temporary name, then rename).
void writeJson(const std::filesystem::path& path, const nlohmann::json& value, int indent = 2);

/// `object[key]`; throws `InputError` "<context>: missing field 'key'" when it is absent, or
/// "<context>: expected a JSON object, found array" when `object` is not an object. `context` names the file and the
/// enclosing object, e.g. "manifest.json: splits".
const nlohmann::json& requireField(const nlohmann::json& object, const std::string& key, const std::string& context);

namespace detail {
template <typename T>
struct IsVector : std::false_type {};
template <typename U>
struct IsVector<std::vector<U>> : std::true_type {};

template <typename T>
const char* jsonKindOf() {
  if constexpr (IsVector<T>::value) {
    using U = typename T::value_type;
    if constexpr (std::is_integral_v<U> && !std::is_same_v<U, bool>) return "an array of integers";
    if constexpr (std::is_arithmetic_v<U>) return "an array of numbers";
    if constexpr (std::is_convertible_v<U, std::string>) return "an array of strings";
    return "an array";
  }
  if constexpr (std::is_same_v<T, bool>) return "true or false";
  if constexpr (std::is_arithmetic_v<T>) return std::is_integral_v<T> ? "an integer" : "a number";
  if constexpr (std::is_convertible_v<T, std::string>) return "a string";
  return "a value of another type";
}

/// Whether `value` is an integer that U holds. nlohmann's get<U> converts out-of-range integers modulo 2^bits
/// ("rows": 4294967300 read as 4, "crc32": -1 as 4294967295), so the range is checked first.
template <typename U>
bool integerFits(const nlohmann::json& value) {
  if (!value.is_number_integer()) return false;
  if (value.is_number_unsigned()) return value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<U>::max());
  const std::int64_t v = value.get<std::int64_t>();
  if constexpr (std::is_signed_v<U>) {
    return v >= static_cast<std::int64_t>(std::numeric_limits<U>::min()) &&
           v <= static_cast<std::int64_t>(std::numeric_limits<U>::max());
  } else {
    return v >= 0 && static_cast<std::uint64_t>(v) <= static_cast<std::uint64_t>(std::numeric_limits<U>::max());
  }
}
}  // namespace detail

/// `object[key]` converted to T when `object` is an object holding the key, else `fallback`; a value of another type
/// is refused as requireValue refuses it (nlohmann's own json.value() throws type_error there, which names no file).
template <typename T>
T valueOr(const nlohmann::json& object, const std::string& key, const T& fallback, const std::string& context);

/// `object[key]` converted to T (a number, bool, string, or anything nlohmann::json converts to); throws
/// `InputError` "<context>: missing field 'key'" or "<context>: field 'key' is a string, expected a number".
template <typename T>
T requireValue(const nlohmann::json& object, const std::string& key, const std::string& context) {
  const nlohmann::json& field = requireField(object, key, context);
  constexpr bool integerWanted = std::is_integral_v<T> && !std::is_same_v<T, bool>;
  if constexpr (integerWanted) {
    PIXELCLOTH_CHECK(!field.is_number_integer() || detail::integerFits<T>(field),
                     context << ": field '" << key << "' is " << field.dump() << ", out of the range of "
                             << detail::jsonKindOf<T>() << " (" << +std::numeric_limits<T>::min() << " to "
                             << +std::numeric_limits<T>::max() << ")");
  }
  PIXELCLOTH_CHECK(!integerWanted || field.is_number_integer(),
                   context << ": field '" << key << "' is " << (field.is_number() ? "" : "a ") << field.type_name()
                           << " " << field.dump() << ", expected " << detail::jsonKindOf<T>());
  if constexpr (detail::IsVector<T>::value) {
    using U = typename T::value_type;
    PIXELCLOTH_CHECK(field.is_array(), context << ": field '" << key << "' is " << field.type_name() << ", expected "
                                               << detail::jsonKindOf<T>());
    if constexpr (std::is_integral_v<U> && !std::is_same_v<U, bool>) {
      for (size_t i = 0; i < field.size(); ++i) {
        const nlohmann::json& item = field[i];
        PIXELCLOTH_CHECK(detail::integerFits<U>(item),
                         context << ": field '" << key << "' entry " << i << " is " << item.dump() << ", expected "
                                 << detail::jsonKindOf<T>());
      }
    }
  }
  try {
    return field.get<T>();
  } catch (const nlohmann::json::exception&) {
    PIXELCLOTH_FAIL(context << ": field '" << key << "' is " << field.type_name() << ", expected "
                            << detail::jsonKindOf<T>());
  }
}

template <typename T>
T valueOr(const nlohmann::json& object, const std::string& key, const T& fallback, const std::string& context) {
  if (!object.is_object() || !object.contains(key)) return fallback;
  return requireValue<T>(object, key, context);
}

}  // namespace pixelcloth::core
