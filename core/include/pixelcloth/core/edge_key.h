#pragma once

#include <cstdint>
#include <utility>

namespace pixelcloth::core {

/// One 64-bit key per undirected mesh edge (a, b), the same for (b, a): for hash maps and sets of edges.
inline std::uint64_t edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace pixelcloth::core
