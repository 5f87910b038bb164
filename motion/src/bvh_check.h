#pragma once
// A structural check of BVH files before assimp reads them. Private to motion/.

#include <string>

namespace pixelcloth::motion::detail {

/// True when `text` is meant as a BVH file: its first word is HIERARCHY.
bool looksLikeBvh(const std::string& text);

/// Checks that `text` (the contents of `file`) is a whole BVH file as assimp 5.2's reader takes it: HIERARCHY, one
/// ROOT, nodes of OFFSET (3 numbers), CHANNELS (0 to 6 of Xposition ... Zrotation), JOINT and End Site blocks in
/// balanced braces at most 256 deep, then MOTION, "Frames:" N >= 1, "Frame Time:" and N frames of one number per
/// channel, every number one that assimp parses whole. Throws InputError naming the file, the line and what was
/// expected otherwise. assimp's reader throws part way through such a file and leaks the nodes it has built (and
/// recurses once per level of nesting), so nothing that fails here reaches it.
void checkBvh(const std::string& text, const std::string& file);

}  // namespace pixelcloth::motion::detail
