#pragma once
// Structural checks of motion clips before assimp reads them: its BVH reader leaks and its glTF readers read past
// the end of damaged files (docs/reliability.md, findings 16 and 17). Private to motion/.

#include <filesystem>
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

/// Checks a glTF clip before assimp reads it: a .gltf file must be a JSON object with an "asset" object (read by
/// core::readJson: size and depth bounded); a .glb file (or one starting with the magic "glTF") must have a binary
/// glTF header whose length is the file's, and a first chunk of JSON (the same test) within it. Throws InputError
/// naming the file otherwise; returns quietly for other files.
void checkGltf(const std::filesystem::path& path, const std::string& extension);

/// What readClip runs before assimp: checkBvh on a BVH file (by its extension or its first word), checkGltf on a glTF
/// or GLB one (by its extension or its magic); other files pass.
void checkBeforeAssimp(const std::filesystem::path& path);

}  // namespace pixelcloth::motion::detail
