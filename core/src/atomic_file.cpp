#include "pixelcloth/core/atomic_file.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

namespace fs = std::filesystem;

void checkOutputFolder(const fs::path& folder) {
  PIXELCLOTH_CHECK(!folder.empty(), "an empty output folder name (--out \"\"): give the folder to write into");
  std::error_code ec;
  PIXELCLOTH_CHECK(!fs::exists(folder, ec) || fs::is_directory(folder, ec),
                   folder.string() << ": exists but is not a folder; expected a folder to write outputs into");
}

void ensureOutputFolder(const fs::path& folder) {
  PIXELCLOTH_CHECK(!folder.empty(), "an empty output folder name (--out \"\"): give the folder to write into");
  std::error_code ec;
  if (fs::exists(folder, ec)) {
    PIXELCLOTH_CHECK(fs::is_directory(folder, ec), folder.string() << ": exists but is not a folder; expected a folder "
                                                                      "to write outputs into");
    return;
  }
  fs::create_directories(folder, ec);
  PIXELCLOTH_CHECK(!ec, folder.string() << ": cannot create the output folder (" << ec.message() << ")");
}

void writeAtomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  PIXELCLOTH_CHECK(!target.empty() && target.has_filename(),
                   "'" << target.string() << "': expected a file name to write (an empty --out?)");
  if (target.has_parent_path()) ensureOutputFolder(target.parent_path());
  fs::path temporary = target;
  temporary += ".tmp-" + std::to_string(::getpid());
  try {
    write(temporary);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::exists(temporary, ec), target.string() << ": the writer produced no file");
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    PIXELCLOTH_FAIL(target.string() << ": cannot move the finished file into place (" << ec.message() << ")");
  }
}

void writeTextAtomically(const fs::path& target, const std::string& text) {
  writeAtomically(target, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    PIXELCLOTH_CHECK(out, target.string() << ": cannot open for writing");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    PIXELCLOTH_CHECK(out, target.string() << ": write failed (disk full?)");
  });
}

std::string readTextFile(const fs::path& path) {
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::exists(path, ec), path.string() << ": no such file");
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), path.string() << ": is not a regular file");
  std::ifstream in(path, std::ios::binary);
  PIXELCLOTH_CHECK(in, path.string() << ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace pixelcloth::core
