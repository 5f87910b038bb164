#pragma once

// The comma-separated text files users bring (pose sequences, marker trajectories): one record a line.

#include <string>
#include <vector>

namespace pixelcloth::core {

/// `text` without the spaces, tabs and line ends around it.
std::string trim(const std::string& text);

/// The fields of one CSV line, each trimmed; a line ending in a comma has an empty last field. No quoting: the files
/// read this way hold numbers.
std::vector<std::string> csvFields(const std::string& line);

}  // namespace pixelcloth::core
