#include "pixelcloth/core/run_folder.h"

#include <array>
#include <utility>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"

namespace pixelcloth::core {

namespace fs = std::filesystem;

namespace {
/// The descriptor files pixelcloth's verbs write at the top of their output folders, and what each one means.
constexpr std::array<std::pair<const char*, const char*>, 12> kDescriptors = {
    {{"manifest.json", "a dataset or base folder"},
     {"model.json", "a model"},
     {"metrics.json", "an evaluation"},
     {"pca.json", "a PCA filter"},
     {"report.json", "a report"},
     {"skeleton.json", "a body"},
     {"garment.json", "a garment"},
     {"stitch.json", "a stitched garment"},
     {"prediction.json", "a prediction"},
     {"motion.json", "a motion"},
     {"dressing.json", "a dressing"},
     {"cage.json", "a cage"}}};

/// What `file` in `folder` holds, for the message: a manifest.json says by its format whether it is a dataset's or a
/// base folder's; a file that cannot be read keeps the general name.
std::string kindOf(const fs::path& folder, const char* file, const char* kind) {
  if (std::string(file) != "manifest.json") return kind;
  try {
    const nlohmann::json manifest = readJson(folder / file);
    const std::string format = manifest.is_object() ? manifest.value("format", std::string()) : std::string();
    if (format == "pixelcloth.dataset") return "a dataset";
    if (format == "pixelcloth.base") return "a base folder";
  } catch (const std::exception&) {
  }
  return kind;
}
}  // namespace

void checkRunFolder(const fs::path& folder, const RunDescription& run) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return;
  for (const auto& [file, kind] : kDescriptors) {
    if (file == run.file || !fs::exists(folder / file, ec)) continue;
    PIXELCLOTH_FAIL(folder.string() << ": holds " << kindOf(folder, file, kind) << " (" << file << "); " << run.what
                                    << " goes in a folder of its own: give another --out");
  }
  if (run.file != kPatchModelFile)
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
      const std::string name = entry.path().filename().string();
      PIXELCLOTH_CHECK(
          !(entry.is_directory(ec) && name.rfind("patch_", 0) == 0 && fs::exists(entry.path() / "model.json", ec)),
          folder.string() << ": holds a patch model (" << name << "/model.json); " << run.what
                          << " goes in a folder of its own: give another --out");
    }
  if (run.file.empty() || run.file == kPatchModelFile || !fs::exists(folder / run.file, ec)) return;
  const fs::path path = folder / run.file;
  const nlohmann::json there = readJson(path);
  PIXELCLOTH_CHECK(there.is_object(), path.string() << ": expected a JSON object");
  for (const auto& [key, value] : run.settings.items()) {
    // Another format in the same descriptor file (a dataset's manifest.json where a base folder's would go): another
    // kind of run.
    PIXELCLOTH_CHECK(key != "format" || (there.contains(key) && there[key] == value),
                     folder.string() << ": holds " << kindOf(folder, run.file.c_str(), "another kind of run") << " ("
                                     << run.file << "); " << run.what
                                     << " goes in a folder of its own: give another --out");
    PIXELCLOTH_CHECK(there.contains(key) && there[key] == value,
                     path.string() << ": the folder holds a run with " << key << " "
                                   << (there.contains(key) ? there[key].dump() : std::string("unset"))
                                   << ", this one's is " << value.dump() << "; writing " << run.what
                                   << " here would mix the two: give another --out, or the same settings");
  }
}

}  // namespace pixelcloth::core
