// Base folders: what is written is read back, and a folder that does not belong to the dataset, or is damaged, is
// refused with a message naming the file.
#include "pixelcloth/data/base_set.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/garment/garment.h"
#include "support/body_fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pd = pixelcloth::data;
namespace pg = pixelcloth::garment;
namespace fs = std::filesystem;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

namespace {

constexpr int kMarkers = 7;

/// A finished necktie dataset of `count` samples on the coarse mannequin (the tie embedded at its closest points).
pd::DatasetInfo writeDataset(const fs::path& folder, int count, std::uint64_t seed) {
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  static const pg::Garment tie = pg::makeNecktie();
  const Eigen::MatrixX3d rest = tie.mesh.V;
  const pg::Embedding embedding = pg::embedClosest(body.mesh.V, body.mesh.F, rest,
                                                   Eigen::RowVector3d(1, 0, 0).replicate(tie.mesh.numVertices(), 1));
  pd::DatasetSettings settings;
  settings.garment = "necktie";
  settings.poseSize = 36;
  settings.vertexCount = tie.mesh.numVertices();
  settings.seed = seed;
  settings.count = count;
  settings.body = {{"kind", "mannequin"}, {"edge_length", 0.02}};
  pd::DatasetWriter writer(folder, settings, body, tie, rest, embedding);
  const pg::EmbeddedFrames frames = pg::embeddedFrames(body.mesh.V, body.mesh.F, embedding);
  for (int i : writer.pending()) {
    pd::Sample sample;
    sample.pose = pb::Pose::identity().toVector().head(36);
    sample.positions = (rest.rowwise() + Eigen::RowVector3d(0, 0, 0.002 * i)).cast<float>();
    sample.offsets = pg::offsetsFromPositions(frames, sample.positions.cast<double>()).cast<float>();
    writer.add(i, sample);
  }
  writer.finish();
  return pd::readDatasetInfo(folder);
}

/// The dataset every test's base folder belongs to: 4 ties.
const pd::DatasetInfo& dataset() {
  static const pd::DatasetInfo info = writeDataset(freshDir("dataset"), 4, 5);
  return info;
}

/// Values that differ everywhere (row, element), so that a transposed or shifted read shows.
Eigen::MatrixXf pattern(int rows, int cols, float scale) {
  Eigen::MatrixXf m(rows, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) m(r, c) = scale * std::sin(0.37f * c + 1.3f * r + 0.1f);
  return m;
}

/// A base folder of dataset() in `folder`.
void writeBase(const fs::path& folder) {
  const pd::DatasetSettings& s = dataset().settings;
  pd::writeBaseSet(folder, dataset(), pattern(s.rows(), 3 * s.vertexCount, 0.01f),
                   pattern(s.rows(), 3 * kMarkers, 0.02f), {{"method", "spline_anisotropic"}, {"noise_cm", 0}});
}

/// Makes the manifest agree with a file that was changed on purpose, so that a later check is what must catch it.
void updateChecksum(const fs::path& folder, const std::string& file) {
  nlohmann::json manifest = pc::readJson(folder / "manifest.json");
  manifest["files"][file] = pd::fileCrc32(folder / file);
  pc::writeJson(folder / "manifest.json", manifest);
}

std::string openError(const fs::path& folder) {
  return inputErrorOf([&] { pd::openBaseSet(folder, dataset()); });
}

}  // namespace

TEST(BaseSet, RoundTripsItsArraysAndManifest) {
  const fs::path folder = freshDir("base");
  writeBase(folder);
  const pd::BaseSet base = pd::openBaseSet(folder, dataset());
  const pd::DatasetSettings& s = dataset().settings;
  EXPECT_EQ(base.samples, 4);
  EXPECT_EQ(base.vertices, s.vertexCount);
  EXPECT_EQ(base.markers, kMarkers);
  EXPECT_EQ(base.offsets, pattern(4, 3 * s.vertexCount, 0.01f));
  EXPECT_EQ(base.features, pattern(4, 3 * kMarkers, 0.02f));
  // Row r, vertex v of the (N, V, 3) array is (du, dv, dn) of that vertex.
  const Eigen::MatrixX3f row2 = base.offsetsOf(2);
  ASSERT_EQ(row2.rows(), s.vertexCount);
  EXPECT_EQ(row2(5, 1), base.offsets(2, 3 * 5 + 1));
  EXPECT_EQ(base.featuresOf(3), base.features.row(3).transpose());
  const pc::NpyArray onDisk = pc::readNpy(folder / "base_offsets.npy");
  EXPECT_EQ(onDisk.shape, (std::vector<std::int64_t>{4, s.vertexCount, 3}));
  EXPECT_EQ(onDisk.data<float>()[(2 * s.vertexCount + 5) * 3 + 1], row2(5, 1));
  EXPECT_EQ(base.manifest["format"], "pixelcloth.base");
  EXPECT_EQ(base.manifest["garment"], "necktie");
  EXPECT_EQ(base.manifest["settings"]["method"], "spline_anisotropic");
  EXPECT_EQ(base.manifest["dataset_manifest_crc32"].get<std::uint32_t>(),
            pd::fileCrc32(dataset().folder / "manifest.json"));
  // Written again over itself: still opens, nothing temporary left.
  writeBase(folder);
  EXPECT_NO_THROW(pd::openBaseSet(folder, dataset()));
  for (const auto& entry : fs::directory_iterator(folder))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

TEST(BaseSet, RefusesABaseFolderOfAnotherDataset) {
  const fs::path folder = freshDir("base");
  writeBase(folder);
  const pd::DatasetInfo other = writeDataset(freshDir("other"), 4, 6);
  const std::string message = inputErrorOf([&] { pd::openBaseSet(folder, other); });
  EXPECT_NE(message.find((folder / "manifest.json").string()), std::string::npos) << message;
  EXPECT_NE(message.find("CRC-32"), std::string::npos) << message;
  EXPECT_NE(message.find("another dataset"), std::string::npos) << message;
  EXPECT_NE(message.find((other.folder / "manifest.json").string()), std::string::npos) << message;
}

TEST(BaseSet, RefusesATruncatedArray) {
  const fs::path folder = freshDir("base");
  writeBase(folder);
  fs::resize_file(folder / "base_offsets.npy", fs::file_size(folder / "base_offsets.npy") - 12);
  const std::string message = openError(folder);
  EXPECT_NE(message.find("base_offsets.npy"), std::string::npos) << message;
}

TEST(BaseSet, RefusesACorruptedArray) {
  const fs::path folder = freshDir("base");
  writeBase(folder);
  {
    std::fstream file(folder / "marker_features.npy", std::ios::in | std::ios::out | std::ios::binary);
    file.seekg(-5, std::ios::end);
    const char byte = static_cast<char>(file.get());
    file.seekp(-5, std::ios::end);
    file.put(static_cast<char>(~byte));
  }
  const std::string message = openError(folder);
  EXPECT_NE(message.find("marker_features.npy"), std::string::npos) << message;
  EXPECT_NE(message.find("CRC-32"), std::string::npos) << message;
}

TEST(BaseSet, RefusesWrongShapes) {
  const pd::DatasetSettings& s = dataset().settings;
  // An array of the wrong shape, its checksum made to agree.
  const fs::path folder = freshDir("base");
  writeBase(folder);
  pc::writeNpy(folder / "base_offsets.npy", std::vector<float>(4 * (s.vertexCount - 1) * 3, 0.f),
               {4, s.vertexCount - 1, 3});
  updateChecksum(folder, "base_offsets.npy");
  std::string message = openError(folder);
  EXPECT_NE(message.find("base_offsets.npy"), std::string::npos) << message;
  EXPECT_NE(message.find("shape (4, " + std::to_string(s.vertexCount - 1) + ", 3)"), std::string::npos) << message;

  // A manifest whose counts disagree with the dataset.
  writeBase(folder);
  nlohmann::json manifest = pc::readJson(folder / "manifest.json");
  manifest["samples"] = 3;
  pc::writeJson(folder / "manifest.json", manifest);
  message = openError(folder);
  EXPECT_NE(message.find("manifest.json: samples 3, expected 4"), std::string::npos) << message;

  // Arrays that do not fit the dataset are not written.
  const fs::path refused = freshDir("refused");
  message = inputErrorOf([&] {
    pd::writeBaseSet(refused, dataset(), Eigen::MatrixXf::Zero(3, 3 * s.vertexCount),
                     Eigen::MatrixXf::Zero(3, 3 * kMarkers), nlohmann::json::object());
  });
  EXPECT_NE(message.find("expected 4 x " + std::to_string(3 * s.vertexCount)), std::string::npos) << message;
  message = inputErrorOf([&] {
    pd::writeBaseSet(refused, dataset(), Eigen::MatrixXf::Zero(4, 3 * s.vertexCount), Eigen::MatrixXf::Zero(4, 8),
                     nlohmann::json::object());
  });
  EXPECT_NE(message.find("marker features of 4 x 8"), std::string::npos) << message;
  Eigen::MatrixXf nan = Eigen::MatrixXf::Zero(4, 3 * kMarkers);
  nan(1, 4) = std::nanf("");
  message = inputErrorOf([&] {
    pd::writeBaseSet(refused, dataset(), Eigen::MatrixXf::Zero(4, 3 * s.vertexCount), nan, nlohmann::json::object());
  });
  EXPECT_NE(message.find("row 1"), std::string::npos) << message;
  EXPECT_TRUE(fs::is_empty(refused));
}

TEST(BaseSet, RefusesAFolderWithoutManifestAndWillNotOverwriteADataset) {
  const fs::path folder = freshDir("base");
  writeBase(folder);
  fs::remove(folder / "manifest.json");
  const std::string message = openError(folder);
  EXPECT_NE(message.find((folder / "manifest.json").string() + ": missing"), std::string::npos) << message;

  const pd::DatasetSettings& s = dataset().settings;
  const std::uint32_t before = pd::fileCrc32(dataset().folder / "manifest.json");
  EXPECT_NE(inputErrorOf([&] {
              pd::writeBaseSet(dataset().folder, dataset(), Eigen::MatrixXf::Zero(4, 3 * s.vertexCount),
                               Eigen::MatrixXf::Zero(4, 3 * kMarkers), nlohmann::json::object());
            }).find("not the manifest of a base folder"),
            std::string::npos);
  EXPECT_EQ(pd::fileCrc32(dataset().folder / "manifest.json"), before);
}
