#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

/// The one way pixelcloth spells an enum in files and on the command line: a fixed table of values and names, looked
/// up both ways. `what` names the enum in messages ("curve method"). Declare one table per enum in its .cpp:
///   const core::EnumNames<CurveMethod, 3> kCurveMethods{
///       "curve method", {{{CurveMethod::Linear, "linear"}, {CurveMethod::CatmullRom, "catmull_rom"}, ...}}};
template <typename E, std::size_t N>
class EnumNames {
 public:
  using Table = std::array<std::pair<E, const char*>, N>;
  EnumNames(const char* what, Table table) : what_(what), table_(table) {}

  /// The name of `value`; "unknown" for a value outside the table (a cast from a corrupt number).
  const char* name(E value) const {
    for (const auto& [v, n] : table_)
      if (v == value) return n;
    return "unknown";
  }
  /// The value named `name`; InputError "<context>: unknown <what> '<name>'; expected a, b or c" otherwise.
  E fromName(const std::string& name, const std::string& context) const {
    for (const auto& [v, n] : table_)
      if (name == n) return v;
    PIXELCLOTH_FAIL(context << ": unknown " << what_ << " '" << name << "'; expected " << list());
  }
  /// Every value, in table order.
  std::vector<E> values() const {
    std::vector<E> out;
    for (const auto& entry : table_) out.push_back(entry.first);
    return out;
  }
  /// "a, b or c".
  std::string list() const {
    std::string out;
    for (std::size_t i = 0; i < N; ++i)
      out += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(table_[i].second);
    return out;
  }

 private:
  const char* what_;
  Table table_;
};

}  // namespace pixelcloth::core
