#pragma once

#include <filesystem>
#include <functional>

namespace pixelcloth::core {

/// Writes `target` through a temporary sibling (`target.tmp-<pid>`) and renames it into place once
/// `write` has returned, so a crash or an exception never leaves a half-written file under the final
/// name. `write` receives the temporary path and must create that file. Creates missing parent
/// folders. On failure the temporary file is removed and the exception propagates; failures of the
/// file system itself (permissions, full disk) become `InputError` naming `target`.
void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

/// Convenience: writes `bytes` to `target` atomically.
void writeTextAtomically(const std::filesystem::path& target, const std::string& text);

/// Reads a whole file; throws `InputError` naming the file when it is missing or unreadable.
std::string readTextFile(const std::filesystem::path& path);

/// Checks, before any work is done, that `folder` can serve as an output folder: it is an existing folder or does not
/// exist yet (it is created when the first file is written). Throws `InputError` when it is a file.
void checkOutputFolder(const std::filesystem::path& folder);

/// Creates `folder` (and parents) or throws `InputError` saying why it cannot be used as an output folder.
void ensureOutputFolder(const std::filesystem::path& folder);

}  // namespace pixelcloth::core
