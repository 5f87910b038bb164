// A dataset's samples on another body: positions kept, embedding and offsets recomputed (docs/dataset.md, "Rebasing").
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/progress.h"
#include "dataset_internal.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data {

namespace fs = std::filesystem;

namespace {

std::string joinedNames(const std::vector<std::string>& names) {
  std::ostringstream out;
  for (size_t i = 0; i < names.size(); ++i) out << (i ? ", " : "") << names[i];
  return out.str();
}

}  // namespace

DatasetSettings rebaseDataset(const DatasetFolder& where, const body::Body& body, const nlohmann::json& bodyDescription,
                              const fs::path& out) {
  const fs::path& folder = where.path;
  const Dataset dataset = openDataset(where);
  const DatasetInfo& info = dataset.info;
  const body::Body old = loadDatasetBody(where);
  PIXELCLOTH_CHECK(body.skeleton.names == old.skeleton.names,
                   "dataset rebase: the body's skeleton has joints " << joinedNames(body.skeleton.names) << "; the "
                                                                      << "poses of " << folder.string()
                                                                      << " are for joints "
                                                                      << joinedNames(old.skeleton.names));
  const int V = dataset.vertexCount();
  const garment::Embedding oldEmbedding = loadDatasetEmbedding(where, old.mesh.numFaces());
  const Eigen::MatrixX3d rest = loadDatasetRestPositions(where, V);
  const garment::Garment garment = datasetGarment(info);
  core::checkOutputFolder(out);

  // The pattern's u-direction at each cloth pixel, as the old embedding carries it on the old rest body.
  const garment::EmbeddedFrames oldFrames = garment::embeddedFrames(old.mesh.V, old.mesh.F, oldEmbedding);
  const garment::Embedding embedding = garment::embedClosest(body.mesh.V, body.mesh.F, rest, oldFrames.t);

  DatasetSettings settings = info.settings;
  settings.body = bodyDescription;
  settings.body["rebased_from"] = {{"folder", fs::absolute(folder).lexically_normal().string()},
                                   {"body", info.settings.body},
                                   {"manifest_crc32", fileCrc32(folder / "manifest.json")}};
  nlohmann::json oldStats = info.manifest.contains("stats") ? info.manifest["stats"] : nlohmann::json();
  settings.generator["rebased_stats"] = oldStats;

  DatasetWriter writer(out, settings, body, garment, rest, embedding);
  const std::vector<int> pending = writer.pending();
  core::Progress progress("dataset rebase", static_cast<std::int64_t>(pending.size()));
  const std::string posesName = (folder / "poses.npy").string();
  for (int index : pending) {
    const int row = index - settings.first();
    writer.add(index, detail::sampleOfPositions(dataset.pose(row), settings.poseSize, dataset.positionsOf(row).cast<double>(),
                                        body, garment, embedding, posesName));
    progress.advance();
  }
  progress.finish();
  writer.finish();
  return settings;
}

}  // namespace pixelcloth::data
