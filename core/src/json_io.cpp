#include "pixelcloth/core/json_io.h"

#include <algorithm>

#include "pixelcloth/core/atomic_file.h"

namespace pixelcloth::core {

namespace fs = std::filesystem;

// The largest JSON file read: a pose list of a long clip is tens of MB. A larger file is refused before it is read
// (read whole and parsed, it would take several times its size in memory).
constexpr std::uintmax_t kMaxJsonBytes = 256u << 20;

nlohmann::json readJson(const fs::path& path) {
  std::error_code ec;
  const std::uintmax_t bytes = fs::is_regular_file(path, ec) ? fs::file_size(path, ec) : 0;
  PIXELCLOTH_CHECK(ec || bytes <= kMaxJsonBytes, path.string() << ": " << bytes << " bytes, more than the "
                                                               << (kMaxJsonBytes >> 20)
                                                               << " MB a JSON file pixelcloth reads may hold");
  return parseJson(readTextFile(path), path.string());
}

nlohmann::json parseJson(const std::string& text, const std::string& context) {
  // Nesting first, outside strings, in one pass over the bytes.
  int depth = 0;
  bool inString = false, escaped = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      PIXELCLOTH_CHECK(++depth <= kMaxJsonDepth,
                       context << ": JSON nested more than " << kMaxJsonDepth << " levels deep (byte " << i + 1 << ")");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based and points just past the offending character.
    const size_t end = std::min(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const size_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
    const size_t lineStart = text.rfind('\n', end == 0 ? 0 : end - 1);
    const size_t column = lineStart == std::string::npos || end == 0 ? end + 1 : end - lineStart;
    std::string reason = e.what();
    const size_t colon = reason.find(": ");  // drop nlohmann's "[json.exception.parse_error.101] parse error at ..."
    if (colon != std::string::npos) reason = reason.substr(colon + 2);
    PIXELCLOTH_FAIL(context << ": invalid JSON at line " << line << ", column " << column << " (byte " << e.byte
                            << "): " << reason);
  } catch (const nlohmann::json::exception& e) {
    // Valid syntax the parser still cannot hold, e.g. a number too large for a double (out_of_range.406).
    std::string reason = e.what();
    const size_t bracket = reason.find("] ");
    if (bracket != std::string::npos) reason = reason.substr(bracket + 2);
    PIXELCLOTH_FAIL(context << ": cannot read the JSON: " << reason);
  }
}

void writeJson(const fs::path& path, const nlohmann::json& value, int indent) {
  std::string text;
  try {
    text = value.dump(indent) + "\n";
  } catch (const nlohmann::json::type_error& e) {  // e.g. a string that is not valid UTF-8
    PIXELCLOTH_FAIL(path.string() << ": cannot write the JSON value (" << e.what() << ")");
  }
  writeTextAtomically(path, text);
}

const nlohmann::json& requireField(const nlohmann::json& object, const std::string& key, const std::string& context) {
  PIXELCLOTH_CHECK(object.is_object(), context << ": expected a JSON object, found " << object.type_name());
  auto it = object.find(key);
  PIXELCLOTH_CHECK(it != object.end(), context << ": missing field '" << key << "'");
  return *it;
}

}  // namespace pixelcloth::core
