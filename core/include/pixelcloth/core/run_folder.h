#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace pixelcloth::core {

/// RunDescription::file of a patch model, whose decoders each describe themselves in a subfolder patch_NN/.
inline constexpr const char* kPatchModelFile = "patch_NN/model.json";

/// What a verb is about to write into its output folder, for the one rule on writing into a folder that is already
/// in use (checkRunFolder).
struct RunDescription {
  /// The file in the folder that describes such a run ("model.json", or kPatchModelFile); empty when the run writes
  /// none of pixelcloth's descriptors.
  std::string file;
  /// Fields of that file that decide what the folder holds; a run with other values would leave a folder whose files
  /// disagree (decoders of two widths), so it is refused. Compared by value; the file must have each one.
  nlohmann::json settings = nlohmann::json::object();
  std::string what;  ///< in messages: "a patch decoder", "a PCA filter"
};

/// The one rule for writing into a folder that exists, applied before anything is written: refused (InputError) when
/// the folder holds another kind of run (another of pixelcloth's descriptor files at its top: a dataset's
/// manifest.json, a model's model.json, an evaluation's metrics.json, a PCA filter's pca.json, a demo's report.json,
/// a body's skeleton.json, a garment's garment.json, a stitched garment's stitch.json, a prediction's
/// prediction.json, a motion's motion.json, a dressing's dressing.json, a cage's cage.json, or a patch model's
/// patch_NN/model.json), or the same kind with other
/// settings (`run.file` whose fields differ
/// from `run.settings`); the message names the file and what differs. A missing or empty folder, or one holding
/// only other files, passes.
void checkRunFolder(const std::filesystem::path& folder, const RunDescription& run);

}  // namespace pixelcloth::core
