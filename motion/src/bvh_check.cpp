#include "bvh_check.h"

#include <array>
#include <cctype>
#include <cstdint>
#include <string_view>

#include "pixelcloth/core/error.h"

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

}  // namespace pixelcloth::motion::detail
