#include "clip_check.h"

#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string_view>
#include <vector>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"

namespace pixelcloth::motion::detail {

namespace {

constexpr int kMaxDepth = 256;
constexpr std::array<std::string_view, 6> kChannels = {"Xposition", "Yposition", "Zposition",
                                                       "Xrotation", "Yrotation", "Zrotation"};

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

/// A number as assimp's fast_atoreal_move reads it whole: a sign, then nan, inf or infinity, or digits (at most 19:
/// more overflow its 64-bit integer and it stops short) with a decimal point and digits, then an exponent of 1 to 19
/// digits. Commas, which assimp would take as decimal points, are refused.
bool isNumber(std::string_view t) {
  size_t i = 0;
  if (i < t.size() && (t[i] == '-' || t[i] == '+')) ++i;
  const std::string_view rest = t.substr(i);
  if (equalsIgnoringCase(rest, "nan") || equalsIgnoringCase(rest, "inf") || equalsIgnoringCase(rest, "infinity"))
    return true;
  size_t digits = 0;
  while (i < t.size() && isDigit(t[i])) ++i, ++digits;
  if (digits > 19) return false;
  size_t fraction = 0;
  if (i < t.size() && t[i] == '.') {
    ++i;
    while (i < t.size() && isDigit(t[i])) ++i, ++fraction;
  }
  if (digits == 0 && fraction == 0) return false;
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '-' || t[i] == '+')) ++i;
    size_t exponent = 0;
    while (i < t.size() && isDigit(t[i])) ++i, ++exponent;
    if (exponent == 0 || exponent > 19) return false;
  }
  return i == t.size();
}

/// The file's words (assimp splits on spaces, tabs and line ends), with the line each is on.
class Words {
 public:
  Words(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  /// The next word, or "" at the end of the file.
  std::string_view next() {
    while (at_ < text_.size() && isSpace(text_[at_])) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
    const size_t start = at_;
    while (at_ < text_.size() && !isSpace(text_[at_])) ++at_;
    return std::string_view(text_).substr(start, at_ - start);
  }

  /// The next word, which must be `keyword`.
  void expect(std::string_view keyword, std::string_view where) {
    const std::string_view word = next();
    PIXELCLOTH_CHECK(word == keyword, place()
                                          << ": expected '" << keyword << "' " << where << ", found " << quoted(word));
  }

  /// The next word as a number.
  std::string_view number(std::string_view what) {
    const std::string_view word = next();
    PIXELCLOTH_CHECK(isNumber(word), place() << ": expected " << what << ", found " << quoted(word));
    return word;
  }

  /// The next word as a whole number in [low, high].
  std::uint64_t count(std::string_view what, std::uint64_t low, std::uint64_t high) {
    const std::string_view word = next();
    std::uint64_t value = 0;
    bool whole = !word.empty() && word.size() <= 19;
    for (const char c : word) {
      whole = whole && isDigit(c);
      if (whole) value = 10 * value + static_cast<std::uint64_t>(c - '0');
    }
    PIXELCLOTH_CHECK(whole && value >= low && value <= high,
                     place() << ": expected " << what << " (" << low << " to " << high << "), found " << quoted(word));
    return value;
  }

  std::string place() const { return file_ + ", line " + std::to_string(line_); }

  static std::string quoted(std::string_view word) {
    if (word.empty()) return "the end of the file";
    std::string shown(word.substr(0, 40));
    for (char& c : shown)
      if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    return "'" + shown + (word.size() > 40 ? "...'" : "'");
  }

 private:
  const std::string& text_;
  const std::string& file_;
  size_t at_ = 0;
  int line_ = 1;
};

void offset(Words& words) {
  for (int k = 0; k < 3; ++k) words.number("an OFFSET coordinate");
}

}  // namespace

bool looksLikeBvh(const std::string& text) {
  size_t i = 0;
  while (i < text.size() && isSpace(text[i])) ++i;
  return text.compare(i, 9, "HIERARCHY") == 0 && (i + 9 == text.size() || isSpace(text[i + 9]));
}

void checkBvh(const std::string& text, const std::string& file) {
  Words words(text, file);
  words.expect("HIERARCHY", "at the start of a BVH file");
  words.expect("ROOT", "after HIERARCHY");
  // The hierarchy, without recursion: `depth` open node blocks.
  std::uint64_t channels = 0;
  int depth = 0;
  bool named = true;  // a ROOT or JOINT word was read: its name and "{" follow
  for (;;) {
    if (!named) {
      const std::string_view word = words.next();
      if (word == "}") {
        if (--depth == 0) break;
        continue;
      }
      if (word == "OFFSET") {
        offset(words);
        continue;
      }
      if (word == "CHANNELS") {
        const std::uint64_t n = words.count("a channel count", 0, 6);
        for (std::uint64_t k = 0; k < n; ++k) {
          const std::string_view name = words.next();
          bool known = false;
          for (const std::string_view channel : kChannels) known = known || name == channel;
          PIXELCLOTH_CHECK(known, words.place() << ": expected a channel (Xposition, Yposition, Zposition, Xrotation, "
                                                   "Yrotation or Zrotation), found "
                                                << Words::quoted(name));
        }
        channels += n;
        continue;
      }
      if (word == "End") {
        words.expect("Site", "after End");
        words.expect("{", "to open an End Site");
        words.expect("OFFSET", "in an End Site");
        offset(words);
        words.expect("}", "to close an End Site");
        continue;
      }
      PIXELCLOTH_CHECK(word == "JOINT", words.place() << ": expected OFFSET, CHANNELS, JOINT, End Site or '}' in a "
                                                         "joint's block, found "
                                                      << Words::quoted(word));
    }
    const std::string_view name = words.next();
    PIXELCLOTH_CHECK(!name.empty() && name != "{" && name != "}",
                     words.place() << ": expected a joint name, found " << Words::quoted(name));
    words.expect("{", "after the joint name");
    PIXELCLOTH_CHECK(++depth <= kMaxDepth, words.place() << ": joints nested more than " << kMaxDepth << " deep");
    named = false;
  }
  PIXELCLOTH_CHECK(channels > 0, words.place() << ": the hierarchy has no CHANNELS; expected a motion clip");
  words.expect("MOTION", "after the hierarchy");
  words.expect("Frames:", "after MOTION");
  const std::uint64_t frames = words.count("a frame count (a BVH needs Frames: 1 or more)", 1, 10000000);
  words.expect("Frame", "after the frame count");
  words.expect("Time:", "after 'Frame'");
  words.number("the frame time");
  // One number per channel and frame; a file that ends early is truncated.
  for (std::uint64_t f = 0; f < frames; ++f)
    for (std::uint64_t c = 0; c < channels; ++c) {
      const std::string_view word = words.next();
      PIXELCLOTH_CHECK(isNumber(word), words.place()
                                           << ": expected " << frames << " frames of " << channels << " numbers; frame "
                                           << f + 1 << ", channel " << c + 1 << " is " << Words::quoted(word)
                                           << (word.empty() ? " (the file is truncated)" : ""));
    }
}

namespace {
void checkGltfJson(const nlohmann::json& json, const std::string& file) {
  PIXELCLOTH_CHECK(json.is_object() && json.contains("asset") && json["asset"].is_object(),
                   file << ": not a glTF file (expected a JSON object with an \"asset\" object)");
}

std::uint32_t littleEndian32(const char* bytes) {
  std::uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = (value << 8) | static_cast<unsigned char>(bytes[k]);
  return value;
}
}  // namespace

void checkGltf(const std::filesystem::path& path, const std::string& extension) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  PIXELCLOTH_CHECK(in, file << ": cannot open for reading");
  char header[20] = {};
  in.read(header, sizeof(header));
  const std::streamsize got = in.gcount();
  const bool binary = got >= 4 && std::memcmp(header, "glTF", 4) == 0;
  if (extension == ".gltf" && !binary) return checkGltfJson(core::readJson(path), file);
  if (extension != ".glb" && !binary) return;
  // Binary glTF: magic, version, total length; version 2: chunks (length, type) with the JSON first; version 1
  // (KHR_binary_glTF): content length and format 0 (JSON), the content after the 20-byte header.
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  PIXELCLOTH_CHECK(!ec && got >= 12 && binary, file << ": not a binary glTF file (expected the magic 'glTF' and a "
                                                       "12-byte header)");
  const std::uint32_t version = littleEndian32(header + 4), length = littleEndian32(header + 8);
  PIXELCLOTH_CHECK(version == 1 || version == 2, file << ": binary glTF version " << version << ", expected 1 or 2");
  PIXELCLOTH_CHECK(length == size, file << ": the binary glTF header says " << length << " bytes, the file has " << size
                                        << " (truncated or damaged)");
  PIXELCLOTH_CHECK(got == 20, file << ": a binary glTF file of " << size << " bytes has no content");
  const std::uint32_t content = littleEndian32(header + 12), kind = littleEndian32(header + 16);
  const std::uint32_t kJson = 0x4E4F534A;  // "JSON"
  PIXELCLOTH_CHECK(version == 2 ? kind == kJson : kind == 0,
                   file << ": the first chunk of a binary glTF file must be its JSON");
  PIXELCLOTH_CHECK(content > 0 && content <= size - 20, file << ": the JSON chunk of " << content
                                                             << " bytes runs past the end of the " << size
                                                             << "-byte file");
  std::string json(content, '\0');
  in.read(json.data(), static_cast<std::streamsize>(content));
  PIXELCLOTH_CHECK(in.gcount() == static_cast<std::streamsize>(content), file << ": cannot read its JSON chunk");
  checkGltfJson(core::parseJson(json, file + " (its JSON chunk)"), file);
  // Version 2: the chunks after the JSON (a BIN chunk) each within the file.
  if (version != 2) return;
  std::uintmax_t at = 20 + static_cast<std::uintmax_t>(content);
  while (at < size) {
    char chunk[8];
    PIXELCLOTH_CHECK(size - at >= 8 && in.read(chunk, 8),
                     file << ": a chunk header at byte " << at << " runs past the end of the file");
    const std::uint32_t bytes = littleEndian32(chunk);
    PIXELCLOTH_CHECK(bytes <= size - at - 8, file << ": the chunk at byte " << at << " says " << bytes
                                                  << " bytes, past the end of the " << size << "-byte file");
    in.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
    at += 8 + bytes;
  }
}

void checkBeforeAssimp(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string head(4096, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  if (extension == ".bvh" || looksLikeBvh(head)) return checkBvh(core::readTextFile(path), path.string());
  checkGltf(path, extension);
}

}  // namespace pixelcloth::motion::detail
