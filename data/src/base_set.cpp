// Base folders of the learned refinement (base_set.h): base offsets and marker features per dataset row, tied to the
// dataset by its manifest's CRC-32.
#include "pixelcloth/data/base_set.h"

#include <cmath>
#include <vector>

#include "dataset_internal.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/npy.h"

namespace pixelcloth::data {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kBaseFormat = "pixelcloth.base";
constexpr int kBaseVersion = 1;
constexpr const char* kBaseOffsets = "base_offsets.npy";
constexpr const char* kMarkerFeatures = "marker_features.npy";

using RowMajorF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// `matrix` (rows x 3K) as a float32 array of shape (rows, K, 3): row r holds K triples, as the matrix row does.
core::NpyArray tripleArray(const Eigen::MatrixXf& matrix) {
  const RowMajorF rowMajor = matrix;
  return core::NpyArray::from(std::vector<float>(rowMajor.data(), rowMajor.data() + rowMajor.size()),
                              {rowMajor.rows(), rowMajor.cols() / 3, 3});
}

/// Reads an array written by tripleArray and checks it against the manifest: dtype and shape (rows, K, 3) first, for
/// the plainest message, then its CRC-32, then its values.
Eigen::MatrixXf readTriples(const fs::path& path, std::int64_t rows, std::int64_t k, std::uint32_t crc,
                            const std::string& manifest, const std::string& what) {
  const std::string file = path.string();
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), file << ": missing (listed in " << manifest << ")");
  const std::vector<std::int64_t> shape = {rows, k, 3};
  const core::NpyHeader header = core::readNpyHeader(path);
  PIXELCLOTH_CHECK(header.dtype == "<f4" && header.shape == shape,
                   file << ": " << header.dtype << " of shape " << header.shapeString() << ", expected <f4 of shape "
                        << core::npyShapeString(shape) << " (" << manifest << ": " << rows << " samples, " << k << " "
                        << what << ")");
  const std::uint32_t actual = fileCrc32(path);
  PIXELCLOTH_CHECK(actual == crc, file << ": CRC-32 " << actual << ", " << manifest << " says " << crc
                                       << " (the file is damaged or was changed)");
  const core::NpyArray array = core::readNpy(path);
  const std::int64_t length = 3 * k;
  detail::checkFinite(array.data<float>(), array.size(), file, 0, length > 0 ? length : 1);
  return Eigen::Map<const RowMajorF>(array.data<float>(), rows, length);
}

}  // namespace

Eigen::MatrixX3f BaseSet::offsetsOf(int row) const {
  PIXELCLOTH_CHECK(row >= 0 && row < samples,
                   folder.string() << ": row " << row << " of the base offsets, the folder has " << samples);
  const Eigen::RowVectorXf values = offsets.row(row);
  return Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>>(values.data(), vertices, 3);
}

Eigen::VectorXf BaseSet::featuresOf(int row) const {
  PIXELCLOTH_CHECK(row >= 0 && row < samples,
                   folder.string() << ": row " << row << " of the marker features, the folder has " << samples);
  return features.row(row).transpose();
}

void writeBaseSet(const fs::path& folder, const DatasetInfo& dataset, const Eigen::MatrixXf& offsets,
                  const Eigen::MatrixXf& features, const json& settings) {
  const DatasetSettings& s = dataset.settings;
  const std::string name = folder.string();
  PIXELCLOTH_CHECK(offsets.rows() == s.rows() && offsets.cols() == 3 * std::int64_t(s.vertexCount),
                   name << ": base offsets of " << offsets.rows() << " x " << offsets.cols() << ", expected "
                        << s.rows() << " x " << 3 * s.vertexCount << " (" << dataset.folder.string() << ": " << s.rows()
                        << " rows, " << s.vertexCount << " vertices)");
  PIXELCLOTH_CHECK(features.rows() == s.rows() && features.cols() % 3 == 0,
                   name << ": marker features of " << features.rows() << " x " << features.cols() << ", expected "
                        << s.rows() << " rows (" << dataset.folder.string() << ") of 3 numbers per marker");
  for (const auto& [what, matrix] :
       {std::pair<const char*, const Eigen::MatrixXf*>{"base offsets", &offsets}, {"marker features", &features}}) {
    if (matrix->allFinite()) continue;
    for (Eigen::Index r = 0; r < matrix->rows(); ++r)
      for (Eigen::Index c = 0; c < matrix->cols(); ++c)
        PIXELCLOTH_CHECK(std::isfinite((*matrix)(r, c)),
                         name << ": " << what << " of row " << r << " (sample " << s.first() + r << "), element ["
                              << c / 3 << ", " << c % 3 << "] is " << (*matrix)(r, c) << ", expected a finite number");
  }
  PIXELCLOTH_CHECK(settings.is_object(),
                   name << ": the settings of a base folder must be a JSON object, got " << settings.type_name());
  std::error_code ec;
  if (fs::exists(folder / detail::kManifest, ec)) {
    // Rewriting a base folder is fine; overwriting a dataset (the base folder given as the dataset itself) is not.
    json old;
    try {
      old = core::readJson(folder / detail::kManifest);
    } catch (const core::InputError&) {
    }
    PIXELCLOTH_CHECK(old.is_object() && old.contains("format") && old["format"] == kBaseFormat,
                     (folder / detail::kManifest).string()
                         << ": exists and is not the manifest of a base folder (format '" << kBaseFormat
                         << "'); refusing to overwrite it: give the base folder a place of its own");
  }
  const std::uint32_t datasetCrc = fileCrc32(dataset.folder / detail::kManifest);

  // An old manifest would vouch for arrays that are being replaced: remove it first, write it again last.
  fs::remove(folder / detail::kManifest, ec);
  core::writeNpy(folder / kBaseOffsets, tripleArray(offsets));
  core::writeNpy(folder / kMarkerFeatures, tripleArray(features));
  const json manifest = {
      {"format", kBaseFormat},
      {"version", kBaseVersion},
      {"dataset", fs::weakly_canonical(fs::absolute(dataset.folder)).string()},
      {"dataset_manifest_crc32", datasetCrc},
      {"garment", s.garment},
      {"samples", s.rows()},
      {"first_sample", s.first()},
      {"vertices", s.vertexCount},
      {"markers", features.cols() / 3},
      {"settings", settings},
      {"files",
       {{kBaseOffsets, fileCrc32(folder / kBaseOffsets)}, {kMarkerFeatures, fileCrc32(folder / kMarkerFeatures)}}}};
  core::writeJson(folder / detail::kManifest, manifest);
}

BaseSet openBaseSet(const fs::path& folder, const DatasetInfo& dataset) {
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_directory(folder, ec), folder.string() << ": no such base folder");
  const fs::path path = folder / detail::kManifest;
  const std::string file = path.string();
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec),
                   file << ": missing; not a base folder, or one whose writing did not finish (pixelcloth "
                           "reconstruct --dataset D --write-base "
                        << folder.string() << " writes one)");
  BaseSet base;
  base.folder = folder;
  base.manifest = core::readJson(path);
  const json& m = base.manifest;
  PIXELCLOTH_CHECK(m.is_object(), file << ": expected a JSON object");
  const std::string format = core::requireValue<std::string>(m, "format", file);
  PIXELCLOTH_CHECK(format == kBaseFormat, file << ": format '" << format << "', expected '" << kBaseFormat << "'");
  const int version = core::requireValue<int>(m, "version", file);
  PIXELCLOTH_CHECK(version == kBaseVersion, file << ": version " << version << ", expected " << kBaseVersion);

  const fs::path datasetManifest = dataset.folder / detail::kManifest;
  const auto madeFrom = core::requireValue<std::uint32_t>(m, "dataset_manifest_crc32", file);
  const std::uint32_t actual = fileCrc32(datasetManifest);
  PIXELCLOTH_CHECK(madeFrom == actual,
                   file << ": made from a dataset whose manifest has CRC-32 " << madeFrom << "; "
                        << datasetManifest.string() << " has " << actual
                        << " (a base folder of another dataset, or of this one before it changed; it was made from "
                        << (m.contains("dataset") ? m["dataset"].dump() : std::string("an unnamed folder")) << ")");

  const DatasetSettings& s = dataset.settings;
  const auto garment = core::requireValue<std::string>(m, "garment", file);
  PIXELCLOTH_CHECK(garment == s.garment, file << ": garment '" << garment << "', " << datasetManifest.string()
                                              << " says '" << s.garment << "'");
  auto expectCount = [&](const char* key, int expected, const char* meaning) {
    const int value = core::requireValue<int>(m, key, file);
    PIXELCLOTH_CHECK(value == expected, file << ": " << key << " " << value << ", expected " << expected << " ("
                                             << datasetManifest.string() << ": " << meaning << ")");
    return value;
  };
  base.samples = expectCount("samples", s.rows(), "its rows");
  expectCount("first_sample", s.first(), "its first sample index");
  base.vertices = expectCount("vertices", s.vertexCount, "vertex_count");
  base.markers = core::requireValue<int>(m, "markers", file);
  PIXELCLOTH_CHECK(base.markers >= 0, file << ": markers " << base.markers << ", expected >= 0");
  PIXELCLOTH_CHECK(core::requireField(m, "settings", file).is_object(),
                   file << ": field 'settings' is " << m["settings"].type_name() << ", expected an object");

  const json& files = core::requireField(m, "files", file);
  PIXELCLOTH_CHECK(files.is_object(),
                   file << ": field 'files' is " << files.type_name() << ", expected an object {file name: CRC-32}");
  const std::string context = file + ": files";
  base.offsets = readTriples(folder / kBaseOffsets, base.samples, base.vertices,
                             core::requireValue<std::uint32_t>(files, kBaseOffsets, context), file, "vertices");
  base.features = readTriples(folder / kMarkerFeatures, base.samples, base.markers,
                              core::requireValue<std::uint32_t>(files, kMarkerFeatures, context), file, "markers");
  return base;
}

}  // namespace pixelcloth::data
