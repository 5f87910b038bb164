// Reading and verifying finished dataset folders.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <tuple>
#include <vector>

#include "dataset_internal.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace detail;

namespace {

/// The manifest's `arrays` (what a reader of another language goes by) agree with its settings, which the arrays
/// themselves are checked against when read: the same file names and shapes.
void checkDeclaredArrays(const json& arrays, const DatasetSettings& s, std::int64_t rows, const std::string& file) {
  PIXELCLOTH_CHECK(arrays.is_object(), file << ": 'arrays' is " << arrays.type_name() << ", expected an object");
  const std::int64_t V = s.vertexCount;
  const std::vector<std::tuple<const char*, const char*, std::vector<std::int64_t>>> expected = {
      {"poses", kPoses, {rows, s.poseSize}},
      {"positions", kPositions, {rows, V, 3}},
      {"offsets", kOffsets, {rows, V, 3}},
      {"split", kSplit, {rows}},
      {"rest_positions", kRestPositions, {V, 3}}};
  for (const auto& [name, fileName, shape] : expected) {
    const std::string where = file + ": arrays: " + name;
    const json& entry = core::requireField(arrays, name, file + ": arrays");
    PIXELCLOTH_CHECK(entry.is_object(), where << " is " << entry.type_name() << ", expected an object");
    const std::string declaredFile = core::requireValue<std::string>(entry, "file", where);
    PIXELCLOTH_CHECK(declaredFile == fileName,
                     where << ": file '" << declaredFile << "', expected '" << fileName << "'");
    const json& declared = core::requireField(entry, "shape", where);
    bool same = declared.is_array() && declared.size() == shape.size();
    for (size_t k = 0; same && k < shape.size(); ++k)
      same = declared[k].is_number_integer() && declared[k].get<std::int64_t>() == shape[k];
    if (!same) {
      std::ostringstream want;
      for (size_t k = 0; k < shape.size(); ++k) want << (k ? ", " : "[") << shape[k];
      PIXELCLOTH_FAIL(where << ": shape " << declared.dump() << ", but the manifest's rows, vertex count and pose size "
                            << "make it " << want.str() << "]");
    }
  }
}

}  // namespace

DatasetInfo readDatasetInfo(const DatasetFolder& where) {
  const fs::path& folder = where.path;
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_directory(folder, ec), folder.string() << ": no such dataset folder");
  const fs::path path = folder / kManifest;
  PIXELCLOTH_CHECK(fs::exists(path, ec), path.string()
                                             << ": missing; "
                                             << (fs::exists(folder / kPartial / "settings.json", ec)
                                                     ? "the dataset is not finished (re-run the same command to "
                                                       "resume it)"
                                                     : "not a dataset folder"));
  const std::string file = path.string();
  DatasetInfo info;
  info.folder = folder;
  info.checksums = where.checksums;
  info.manifest = core::readJson(path);
  const json& m = info.manifest;
  PIXELCLOTH_CHECK(m.is_object(), file << ": expected a JSON object");
  if (m.contains("format")) {  // written since the first version; a hand-made manifest may leave it out
    const std::string format = core::requireValue<std::string>(m, "format", file);
    PIXELCLOTH_CHECK(format == "pixelcloth.dataset",
                     file << ": format '" << format << "', expected 'pixelcloth.dataset' (a dataset's manifest)");
  }
  const int version = core::requireValue<int>(m, "format_version", file);
  PIXELCLOTH_CHECK(version == kDatasetFormatVersion,
                   file << ": format_version " << version << ", expected " << kDatasetFormatVersion);
  info.settings = DatasetSettings::fromJson(m, file);
  const int rows = core::requireValue<int>(m, "rows", file);
  PIXELCLOTH_CHECK(rows == info.settings.rows(), file << ": rows " << rows << ", but shard "
                                                      << info.settings.shard.toString() << " of " << info.settings.count
                                                      << " samples has " << info.settings.rows());
  if (m.contains("arrays")) checkDeclaredArrays(m["arrays"], info.settings, rows, file);
  const json& counts = core::requireField(m, "counts", file);
  info.counts.train = core::requireValue<int>(counts, "train", file + ": counts");
  info.counts.regularisation = core::requireValue<int>(counts, "regularisation", file + ": counts");
  info.counts.test = core::requireValue<int>(counts, "test", file + ": counts");
  PIXELCLOTH_CHECK(info.counts.total() == rows,
                   file << ": counts add up to " << info.counts.total() << ", rows is " << rows);
  info.stats = DatasetStats::fromJson(core::requireField(m, "stats", file), file + ": stats");
  const json& checksums = core::requireField(m, "checksums", file);
  PIXELCLOTH_CHECK(checksums.is_object(), file << ": checksums must be an object {file: {crc32, bytes}}");
  for (const char* required : {kPoses, kPositions, kOffsets, kSplit, kRestPositions})
    PIXELCLOTH_CHECK(checksums.contains(required), file << ": checksums: missing '" << required << "'");
  for (const auto& [name, entry] : checksums.items()) {
    core::requireValue<std::uint32_t>(entry, "crc32", file + ": checksums: " + name);
    core::requireValue<std::uint64_t>(entry, "bytes", file + ": checksums: " + name);
    PIXELCLOTH_CHECK(name.find("..") == std::string::npos && !name.empty() && name[0] != '/',
                     file << ": checksums: '" << name << "' is not a path inside the dataset");
  }
  return info;
}

int DatasetInfo::rowOfSample(int sample, const std::string& what) const {
  PIXELCLOTH_CHECK(sample >= settings.first() && sample < settings.end(),
                   what << " " << sample << ": " << folder.string() << " holds samples " << settings.first() << " to "
                        << settings.end() - 1);
  return sample - settings.first();
}

std::string DatasetInfo::summary() const {
  const DatasetSettings& s = settings;
  std::ostringstream out;
  out << std::fixed;
  out << "dataset      " << folder.string() << " (format " << kDatasetFormatVersion << ", " << s.source << ")\n";
  out << "garment      " << s.garment << ", " << s.vertexCount << " vertices, pose vectors of " << s.poseSize
      << " floats\n";
  out << "body         " << s.body.dump() << "\n";
  out << "samples      " << s.rows() << " (indices " << s.first() << " to " << s.end() - 1 << " of " << s.count
      << ", shard " << s.shard.toString() << "), seed " << s.seed << "\n";
  auto percent = [&](int n) { return s.rows() ? 100.0 * n / s.rows() : 0.0; };
  out << std::setprecision(1) << "splits       train " << counts.train << " (" << percent(counts.train)
      << "%), regularisation " << counts.regularisation << " (" << percent(counts.regularisation) << "%), test "
      << counts.test << " (" << percent(counts.test) << "%)\n";
  const json st = stats.toJson();
  out << std::setprecision(2) << "solver       accepted " << stats.accepted << ", mean iterations "
      << st["mean_iterations"].get<double>() << " (max " << stats.maxIterations << "), mean "
      << st["mean_seconds"].get<double>() << " s per sample, " << stats.sumSeconds << " s in all\n";
  out << std::setprecision(3);
  if (std::isfinite(stats.maxResidualForceRatio))
    out << "equilibrium  largest net force on a vertex " << 100 * stats.maxResidualForceRatio
        << "% of its weight (Newton solver)\n";
  out << "penetration  max " << stats.maxPenetration * 1000.0 << " mm\n";
  if (stats.accepted > 0)
    out << "area ratio   " << stats.minAreaRatio << " to " << stats.maxAreaRatio << " (3D area / pattern area)\n";
  out << "rejected     " << stats.rejectedTotal();
  std::string sep = " (";
  for (const auto& [reason, n] : stats.rejected) {
    out << sep << reason << " " << n;
    sep = ", ";
  }
  out << (stats.rejected.empty() ? "" : ")") << "\n";
  out << "settings     " << s.generator.dump() << "\n";
  return out.str();
}

// ---------------------------------------------------------------------------------------------------------------------
// Dataset

namespace {

/// A float32 array of `shape`: dtype and shape checked from the header before the data is read, every value checked
/// to be finite after (a NaN would reach training as a NaN loss).
core::NpyArray readFloatArray(const fs::path& path, const std::vector<std::int64_t>& shape) {
  const core::NpyHeader header = core::readNpyHeader(path);
  PIXELCLOTH_CHECK(header.dtype == "<f4" && header.shape == shape,
                   path.string() << ": dtype " << header.dtype << ", shape " << header.shapeString()
                                 << ", expected <f4 " << core::npyShapeString(shape));
  core::NpyArray array = core::readNpy(path);
  array.checkDtype("<f4");
  PIXELCLOTH_CHECK(array.shape == shape,
                   path.string() << ": shape " << array.shapeString() << ", expected " << core::npyShapeString(shape));
  const std::int64_t rowLength = shape.size() > 1 ? array.size() / std::max<std::int64_t>(shape[0], 1) : 1;
  detail::checkFinite(array.data<float>(), array.size(), path.string(), 0, std::max<std::int64_t>(rowLength, 1));
  return array;
}

Eigen::MatrixX3f rowBlock(const core::NpyArray& array, int row, int vertices) {
  const float* p = array.data<float>() + std::int64_t(row) * vertices * 3;
  return Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>>(p, vertices, 3);
}

}  // namespace

Eigen::VectorXf Dataset::pose(int row) const { return poses.row(row).transpose(); }
Eigen::MatrixX3f Dataset::positionsOf(int row) const { return rowBlock(positions, row, vertexCount()); }
Eigen::MatrixX3f Dataset::offsetsOf(int row) const { return rowBlock(offsets, row, vertexCount()); }

std::vector<int> Dataset::rowsOf(Split which) const {
  std::vector<int> result;
  for (int r = 0; r < rows(); ++r)
    if (split[r] == static_cast<std::uint8_t>(which)) result.push_back(r);
  return result;
}

namespace {
/// Verifies every file the manifest of `folder` lists whose name starts with `prefix` ("body/", "embedding"). A
/// folder without manifest.json (a dressing folder: body/, embedding and rest positions only) has nothing to check.
void verifyFilesStartingWith(const DatasetFolder& folder, const std::string& prefix) {
  std::error_code ec;
  if (folder.checksums == Checksums::Skip || !fs::is_regular_file(folder.path / kManifest, ec)) return;
  const DatasetInfo info = readDatasetInfo(folder);
  for (const auto& [name, entry] : info.manifest["checksums"].items())
    if (name.rfind(prefix, 0) == 0) verifyDatasetFile(info, name);
}
}  // namespace

void verifyDatasetFile(const DatasetInfo& info, const std::string& name) {
  if (info.checksums == Checksums::Skip) return;
  const json& checksums = info.manifest["checksums"];
  if (!checksums.contains(name)) return;
  const fs::path path = info.folder / name;
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), path.string() << ": missing (listed in manifest.json checksums)");
  const auto bytes = checksums[name]["bytes"].get<std::uint64_t>();
  const std::uintmax_t size = fs::file_size(path, ec);
  PIXELCLOTH_CHECK(size == bytes, path.string() << ": " << size << " bytes, manifest.json says " << bytes
                                                << " (the file is damaged or was changed; --no-verify reads it anyway)");
  const std::uint32_t crc = fileCrc32(path), expected = checksums[name]["crc32"].get<std::uint32_t>();
  PIXELCLOTH_CHECK(crc == expected, path.string() << ": CRC-32 " << crc << ", manifest.json says " << expected
                                                  << " (the file is damaged or was changed; --no-verify reads it anyway)");
}

Dataset openDataset(const DatasetFolder& where) {
  const fs::path& folder = where.path;
  Dataset d;
  d.info = readDatasetInfo(where);
  for (const char* name : {kPoses, kPositions, kOffsets, kSplit}) verifyDatasetFile(d.info, name);
  const DatasetSettings& s = d.info.settings;
  const std::int64_t rows = s.rows(), V = s.vertexCount;
  d.poses = core::readNpyMatrixF(folder / kPoses, rows, s.poseSize);
  d.positions = readFloatArray(folder / kPositions, {rows, V, 3});
  d.offsets = readFloatArray(folder / kOffsets, {rows, V, 3});
  const core::NpyHeader splitHeader = core::readNpyHeader(folder / kSplit);  // checked before the data is read
  PIXELCLOTH_CHECK(splitHeader.shape == std::vector<std::int64_t>{rows}, (folder / kSplit).string()
                                                                             << ": shape " << splitHeader.shapeString()
                                                                             << ", expected (" << rows << ",)");
  const core::NpyArray split = core::readNpy(folder / kSplit);
  split.checkDtype("|u1");
  d.split.assign(split.bytes.begin(), split.bytes.end());
  for (std::int64_t r = 0; r < rows; ++r) {
    const Eigen::VectorXf pose = d.poses.row(r).transpose();  // poses is column-major: one row at a time
    detail::checkFinite(pose.data(), pose.size(), (folder / kPoses).string(), r * pose.size(),
                        std::max<std::int64_t>(pose.size(), 1));
  }
  for (std::int64_t r = 0; r < rows; ++r)
    PIXELCLOTH_CHECK(d.split[r] <= 2, (folder / kSplit).string() << ": row " << r + 1 << " has split value "
                                                                 << int(d.split[r]) << ", expected 0, 1 or 2");
  return d;
}

body::Body loadDatasetBody(const DatasetFolder& folder) {
  verifyFilesStartingWith(folder, "body/");
  return body::loadBody(folder.path / "body");
}

garment::Embedding loadDatasetEmbedding(const DatasetFolder& folder, int numBodyFaces) {
  verifyFilesStartingWith(folder, "embedding");
  return garment::loadEmbedding(folder.path, numBodyFaces);
}

Eigen::MatrixX3d loadDatasetRestPositions(const DatasetFolder& folder, int vertexCount) {
  verifyFilesStartingWith(folder, kRestPositions);
  return core::readNpyMatrixD(folder.path / kRestPositions, vertexCount, 3);
}

DressingFiles loadDressingFiles(const DatasetFolder& folder, const garment::Garment& garment,
                                const std::string& garmentSource) {
  const int V = garment.mesh.numVertices();
  const fs::path restFile = folder.path / kRestPositions;
  const core::NpyHeader restHeader = core::readNpyHeader(restFile);
  const std::int64_t restRows = restHeader.shape.empty() ? 0 : restHeader.shape[0];
  PIXELCLOTH_CHECK(restRows == V, restFile.string()
                                      << ": shape " << restHeader.shapeString() << ": the dressing is of a garment of "
                                      << restRows << " vertices, "
                                      << (garmentSource.empty() ? "" : garmentSource + " are of ") << "the "
                                      << garment.name << " (" << V << " vertices): the garments differ");
  DressingFiles out;
  out.body = loadDatasetBody(folder);
  out.rest = loadDatasetRestPositions(folder, V);
  out.embedding = loadDatasetEmbedding(folder, out.body.mesh.numFaces());
  PIXELCLOTH_CHECK(out.embedding.size() == V, (folder.path / "embedding_triangle.npy").string()
                                                  << ": " << out.embedding.size() << " cloth pixels, the "
                                                  << garment.name << " has " << V);
  return out;
}

garment::Garment datasetGarment(const DatasetInfo& info) {
  verifyFilesStartingWith({info.folder, info.checksums}, "garment/");
  const fs::path folder = info.folder / "garment";
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(folder / "garment.obj", ec) && fs::is_regular_file(folder / "garment.json", ec),
                   folder.string() << ": missing garment.obj or garment.json; a dataset carries the garment it was "
                                      "made with (docs/dataset.md)");
  garment::Garment garment = garment::loadGarment(folder);
  PIXELCLOTH_CHECK(garment.mesh.numVertices() == info.settings.vertexCount,
                   folder.string() << ": the garment has " << garment.mesh.numVertices() << " vertices, "
                                   << (info.folder / kManifest).string() << " says vertex_count "
                                   << info.settings.vertexCount);
  PIXELCLOTH_CHECK(garment.traits.poseSize() == info.settings.poseSize,
                   folder.string() << ": the garment is driven by " << garment.traits.poseJoints << " joints ("
                                   << garment.traits.poseSize() << " pose floats), " << (info.folder / kManifest).string()
                                   << " says pose_size " << info.settings.poseSize);
  return garment;
}

// ---------------------------------------------------------------------------------------------------------------------
// checkDataset

std::string DatasetCheckReport::summary() const {
  std::ostringstream out;
  out << rows << " samples, " << filesChecked << " files match their checksums, offsets of " << strongSamples
      << " samples recomputed (max difference " << std::scientific << std::setprecision(2) << maxOffsetError << " m)";
  return out.str();
}

DatasetCheckReport checkDataset(const fs::path& folder, const DatasetCheckOptions& options) {
  DatasetCheckReport report;
  const DatasetInfo info = readDatasetInfo(folder);
  const DatasetSettings& s = info.settings;
  const std::int64_t rows = s.rows(), V = s.vertexCount;
  report.rows = static_cast<int>(rows);
  std::error_code ec;

  // Sizes and CRCs of every file the manifest lists.
  for (const auto& [name, entry] : info.manifest["checksums"].items()) {
    const fs::path path = folder / name;
    PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), path.string() << ": missing (listed in manifest.json checksums)");
    const auto bytes = entry["bytes"].get<std::uint64_t>();
    PIXELCLOTH_CHECK(fs::file_size(path, ec) == bytes,
                     path.string() << ": " << fs::file_size(path, ec) << " bytes, manifest.json says " << bytes);
    const std::uint32_t crc = fileCrc32(path), expected = entry["crc32"].get<std::uint32_t>();
    PIXELCLOTH_CHECK(crc == expected, path.string() << ": CRC-32 " << crc << ", manifest.json says " << expected
                                                    << " (the file is damaged or was changed)");
    ++report.filesChecked;
  }

  // Shapes and dtypes.
  auto expectHeader = [&](const char* name, const std::string& dtype, const std::vector<std::int64_t>& shape) {
    const core::NpyHeader h = core::readNpyHeader(folder / name);
    PIXELCLOTH_CHECK(h.dtype == dtype && h.shape == shape,
                     (folder / name).string() << ": " << h.dtype << " of shape " << h.shapeString() << ", expected "
                                              << dtype << " of shape " << core::npyShapeString(shape)
                                              << " (manifest.json: " << rows << " rows, " << V << " vertices)");
    return h;
  };
  const core::NpyHeader posesHeader = expectHeader(kPoses, "<f4", {rows, s.poseSize});
  const core::NpyHeader positionsHeader = expectHeader(kPositions, "<f4", {rows, V, 3});
  const core::NpyHeader offsetsHeader = expectHeader(kOffsets, "<f4", {rows, V, 3});
  const core::NpyHeader splitHeader = expectHeader(kSplit, "|u1", {rows});

  // Values: finite, poses are rotations, splits valid and as the seed says.
  core::Progress progress("dataset check", 3 * rows);
  std::vector<float> buffer;
  for (const auto& [name, header] : {std::pair<const char*, const core::NpyHeader*>{kPoses, &posesHeader},
                                     {kPositions, &positionsHeader},
                                     {kOffsets, &offsetsHeader}}) {
    const fs::path path = folder / name;
    std::ifstream in(path, std::ios::binary);
    const std::int64_t rowLength = header->elements() / std::max<std::int64_t>(rows, 1);
    buffer.resize(rowLength);
    for (std::int64_t r = 0; r < rows; ++r) {
      readAt(in, path, header->dataOffset + r * rowLength * 4, buffer.data(), rowLength * 4);
      checkFinite(buffer.data(), rowLength, path.string(), r * rowLength, rowLength);
      if (name == std::string(kPoses)) {
        body::Pose::fromLeading(Eigen::Map<const Eigen::VectorXf>(buffer.data(), s.poseSize),
                                path.string() + ": row " + std::to_string(r + 1));
      }
      progress.advance();
    }
  }
  progress.finish();
  {
    std::vector<std::uint8_t> split(rows);
    std::ifstream in(folder / kSplit, std::ios::binary);
    readAt(in, folder / kSplit, splitHeader.dataOffset, split.data(), rows);
    const std::vector<std::uint8_t> expected = datasetSplit(s.seed, s.count);
    for (std::int64_t r = 0; r < rows; ++r) {
      PIXELCLOTH_CHECK(split[r] <= 2, (folder / kSplit).string() << ": row " << r + 1 << " has split value "
                                                                 << int(split[r]) << ", expected 0, 1 or 2");
      PIXELCLOTH_CHECK(split[r] == expected[s.first() + r],
                       (folder / kSplit).string()
                           << ": row " << r + 1 << " (sample " << s.first() + r << ") is " << splitName(Split(split[r]))
                           << ", but seed " << s.seed << " and " << s.count << " samples make it "
                           << splitName(Split(expected[s.first() + r])));
    }
    const SplitCounts counts = countSplits(split);
    PIXELCLOTH_CHECK(counts.train == info.counts.train && counts.regularisation == info.counts.regularisation &&
                         counts.test == info.counts.test,
                     (folder / kSplit).string()
                         << ": " << counts.train << "/" << counts.regularisation << "/" << counts.test
                         << " samples per split, manifest.json counts say " << info.counts.train << "/"
                         << info.counts.regularisation << "/" << info.counts.test);
  }

  // Strong check: offsets recomputed from positions on the stored body with the stored embedding.
  if (options.strongSamples > 0 && rows > 0) {
    const body::Body body = loadDatasetBody(folder);
    const garment::Embedding embedding = loadDatasetEmbedding(folder, body.mesh.numFaces());
    PIXELCLOTH_CHECK(embedding.size() == V, folder.string() << "/embedding_triangle.npy: " << embedding.size()
                                                            << " cloth pixels, manifest.json says " << V);
    loadDatasetRestPositions(folder, static_cast<int>(V));
    std::ifstream posesIn(folder / kPoses, std::ios::binary), positionsIn(folder / kPositions, std::ios::binary),
        offsetsIn(folder / kOffsets, std::ios::binary);
    const int n = static_cast<int>(std::min<std::int64_t>(options.strongSamples, rows));
    for (int k = 0; k < n; ++k) {
      const std::int64_t r = n == 1 ? 0 : k * (rows - 1) / (n - 1);
      Eigen::VectorXf pose(s.poseSize);
      readAt(posesIn, folder / kPoses, posesHeader.dataOffset + r * s.poseSize * 4, pose.data(), s.poseSize * 4);
      using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;
      RowMatrix positions(V, 3), offsets(V, 3);
      readAt(positionsIn, folder / kPositions, positionsHeader.dataOffset + r * V * 12, positions.data(), V * 12);
      readAt(offsetsIn, folder / kOffsets, offsetsHeader.dataOffset + r * V * 12, offsets.data(), V * 12);
      const body::Pose posed = body::Pose::fromLeading(pose, (folder / kPoses).string());
      const garment::EmbeddedFrames frames = garment::embeddedFrames(body.posedVertices(posed), body.mesh.F, embedding);
      const Eigen::MatrixX3d recomputed = garment::offsetsFromPositions(frames, positions.cast<double>());
      Eigen::Index worst = 0;
      const double error = (recomputed - offsets.cast<double>()).rowwise().norm().maxCoeff(&worst);
      report.maxOffsetError = std::max(report.maxOffsetError, error);
      ++report.strongSamples;
      PIXELCLOTH_CHECK(error <= options.tolerance,
                       (folder / kOffsets).string()
                           << ": row " << r + 1 << " (sample " << s.first() + r << "), vertex " << worst + 1
                           << " (counting from 1): stored offsets differ by " << error
                           << " m from those recomputed from positions.npy on the stored "
                           << "body and embedding (tolerance " << options.tolerance << " m)");
    }
  }
  return report;
}

}  // namespace pixelcloth::data
