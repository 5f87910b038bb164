// Dataset folders: writing, resuming, merging shards, checking, importing.
#include "pixelcloth/data/dataset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <set>
#include <thread>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/data/face_statistics.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pd = pixelcloth::data;
namespace pg = pixelcloth::garment;
namespace fs = std::filesystem;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

namespace {

/// The T-shirt's rest placement embedded on the coarse mannequin by closest point.
struct Fixture {
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  const pg::Garment& garment = pixelcloth::testing::tshirt();
  Eigen::MatrixX3d rest;
  pg::Embedding embedding;
  Eigen::MatrixX3d restOffsets;

  Fixture() {
    rest = garment.mesh.V;
    const Eigen::MatrixX3d normals = pc::vertexNormals(garment.mesh.V, garment.mesh.F);
    Eigen::MatrixX3d u(rest.rows(), 3);
    for (int i = 0; i < rest.rows(); ++i)
      u.row(i) = std::abs(normals(i, 0)) < 0.8 ? Eigen::RowVector3d(1, 0, 0) : Eigen::RowVector3d(0, 1, 0);
    embedding = pg::embedClosest(body.mesh.V, body.mesh.F, rest, u);
    restOffsets = pg::offsetsFromPositions(pg::embeddedFrames(body.mesh.V, body.mesh.F, embedding), rest);
  }

  pd::DatasetSettings settings(int count, std::uint64_t seed = 7, pd::DatasetShard shard = {}) const {
    pd::DatasetSettings s;
    s.garment = "tshirt";
    s.poseSize = 90;
    s.vertexCount = garment.mesh.numVertices();
    s.seed = seed;
    s.count = count;
    s.shard = shard;
    s.body = {{"kind", "mannequin"}, {"shape", 0}, {"edge_length", 0.02}};
    s.generator = {{"solver", "synthetic"}, {"steps", 3}};
    return s;
  }

  /// Sample `index`: a random pose, offsets = rest offsets plus a small index-dependent wave, positions from them.
  pd::Sample sample(int index) const {
    const pb::Pose pose = pb::randomPose(1000 + index, 0.3);
    Eigen::MatrixX3d offsets = restOffsets;
    for (int v = 0; v < offsets.rows(); ++v) offsets(v, 2) += 0.002 * std::sin(0.1 * v + index);
    const pg::EmbeddedFrames frames = pg::embeddedFrames(body.posedVertices(pose), body.mesh.F, embedding);
    pd::Sample s;
    s.pose = pose.toVector();
    s.positions = pg::positionsFromOffsets(frames, offsets).cast<float>();
    // What a solver stores: the offsets of the (float) positions it wrote.
    s.offsets = pg::offsetsFromPositions(frames, s.positions.cast<double>()).cast<float>();
    s.stats.iterations = 10 + index;
    s.stats.extraRounds = index % 3 == 0 ? 1 : 0;
    if (index % 2 == 0) {  // as the Newton solver measures them (odd samples: not measured, as by the other solver)
      s.stats.maxResidualForce = 1e-6 * index;
      s.stats.residualForceRatio = 0.001 * index;
    }
    s.stats.maxPenetration = 0.0001 * index;
    s.stats.minAreaRatio = 0.9 - 0.001 * index;
    s.stats.maxAreaRatio = 1.1 + 0.001 * index;
    s.stats.seconds = 0.5;
    return s;
  }

  void writeAll(const fs::path& folder, const pd::DatasetSettings& s, int chunkSize = 4) const {
    pd::DatasetWriter writer(folder, s, body, garment, rest, embedding, {chunkSize});
    for (int i : writer.pending()) writer.add(i, sample(i));
    writer.finish();
  }
};

const Fixture& setup() {
  static const Fixture s;
  return s;
}

std::uint32_t manifestCrc(const fs::path& folder, const std::string& file) {
  return pc::readJson(folder / "manifest.json")["checksums"][file]["crc32"].get<std::uint32_t>();
}

/// Makes the manifest agree with a file that was changed on purpose, so that a later check is what must catch it.
void updateChecksum(const fs::path& folder, const std::string& file) {
  nlohmann::json manifest = pc::readJson(folder / "manifest.json");
  manifest["checksums"][file] = {{"crc32", pd::fileCrc32(folder / file)}, {"bytes", fs::file_size(folder / file)}};
  pc::writeJson(folder / "manifest.json", manifest);
}

void copyFolder(const fs::path& from, const fs::path& to) {
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
}

bool hasTemporaries(const fs::path& folder) {
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(DatasetSplit, IsEightyTenTenDeterministicAndSeeded) {
  const std::vector<std::uint8_t> a = pd::datasetSplit(7, 1000), b = pd::datasetSplit(7, 1000);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, pd::datasetSplit(8, 1000));
  const pd::SplitCounts counts = pd::countSplits(a);
  EXPECT_EQ(counts.train, 800);
  EXPECT_EQ(counts.regularisation, 100);
  EXPECT_EQ(counts.test, 100);
  // Not simply the first 800 indices: the test samples are spread over the whole range.
  int testInFirstHalf = 0;
  for (int i = 0; i < 500; ++i) testInFirstHalf += a[i] == 2;
  EXPECT_GT(testInFirstHalf, 25);
  EXPECT_LT(testInFirstHalf, 75);
}

TEST(DatasetShard, ShardsTileTheIndicesAndParse) {
  for (int count : {1, 7, 100}) {
    for (int shards : {1, 3, 7}) {
      if (shards > count) continue;
      int next = 0;
      for (int k = 0; k < shards; ++k) {
        pd::DatasetShard shard{k, shards};
        EXPECT_EQ(shard.first(count), next);
        EXPECT_GE(shard.end(count), shard.first(count));
        next = shard.end(count);
      }
      EXPECT_EQ(next, count);
    }
  }
  const pd::DatasetShard shard = pd::parseShard("3/100");
  EXPECT_EQ(shard.index, 3);
  EXPECT_EQ(shard.count, 100);
  EXPECT_NE(inputErrorOf([] { pd::parseShard("100/100"); }).find("0 <= K < N"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { pd::parseShard("3"); }).find("K/N"), std::string::npos);
}

TEST(DatasetWriter, WritesADatasetThatOpensAndChecks) {
  const Fixture& s = setup();
  const fs::path folder = freshDir("dataset");
  const int n = 12;
  {
    pd::DatasetWriter writer(folder, s.settings(n), s.body, s.garment, s.rest, s.embedding, {5});
    EXPECT_FALSE(writer.resumed());
    ASSERT_EQ(writer.pending().size(), static_cast<size_t>(n));
    // Two threads, as the generator runs.
    std::thread other([&] {
      for (int i = 1; i < n; i += 2) writer.add(i, s.sample(i));
    });
    for (int i = 0; i < n; i += 2) writer.add(i, s.sample(i));
    other.join();
    writer.countRejection(pd::Rejection::TriangleShrank);
    writer.countRejection(pd::Rejection::TriangleShrank);
    writer.countRejection(pd::Rejection::TriangleGrew);
    EXPECT_TRUE(writer.pending().empty());
    writer.finish();
  }
  for (const char* file : {"manifest.json", "poses.npy", "positions.npy", "offsets.npy", "split.npy",
                           "rest_positions.npy", "embedding_triangle.npy", "embedding_barycentric.npy",
                           "embedding_tangent.npy", "body/body.obj", "body/weights.npy", "garment/garment.obj"})
    EXPECT_TRUE(fs::exists(folder / file)) << file;
  EXPECT_FALSE(fs::exists(folder / "partial"));
  EXPECT_FALSE(hasTemporaries(folder));

  const pd::Dataset d = pd::openDataset(folder);
  ASSERT_EQ(d.rows(), n);
  for (int i : {0, 5, 11}) {
    const pd::Sample expected = s.sample(i);
    EXPECT_EQ(d.pose(i), expected.pose);
    EXPECT_EQ(d.positionsOf(i), expected.positions);
    EXPECT_EQ(d.offsetsOf(i), expected.offsets);
  }
  EXPECT_EQ(d.split, pd::datasetSplit(7, n));
  EXPECT_EQ(d.info.counts.train, 10);
  EXPECT_EQ(d.info.counts.regularisation, 1);
  EXPECT_EQ(d.info.counts.test, 1);
  EXPECT_EQ(d.info.stats.accepted, n);
  EXPECT_EQ(d.info.stats.rejected.at("triangle_shrank"), 2);
  EXPECT_EQ(d.info.stats.rejected.at("triangle_grew"), 1);
  EXPECT_NEAR(d.info.stats.maxPenetration, 0.0011, 1e-12);
  EXPECT_EQ(d.info.stats.maxIterations, 21);
  EXPECT_EQ(d.info.stats.acceptedAfterExtra, 4);  // samples 0, 3, 6 and 9
  EXPECT_NEAR(d.info.stats.maxResidualForceRatio, 0.010, 1e-12);  // sample 10
  const nlohmann::json manifest = d.info.manifest;
  EXPECT_EQ(manifest["format_version"], pd::kDatasetFormatVersion);
  EXPECT_NEAR(manifest["stats"]["max_penetration_mm"].get<double>(), 1.1, 1e-9);
  EXPECT_NEAR(manifest["stats"]["max_residual_force_ratio"].get<double>(), 0.010, 1e-12);
  EXPECT_EQ(manifest["source"], "simulated");
  EXPECT_EQ(manifest["settings"]["steps"], 3);

  const pd::DatasetCheckReport report = pd::checkDataset(folder);
  EXPECT_EQ(report.rows, n);
  EXPECT_EQ(report.strongSamples, 3);
  EXPECT_LT(report.maxOffsetError, 1e-5);
  EXPECT_GE(report.filesChecked, 12);

  // The stored body and embedding are what was given.
  const pg::Embedding embedding = pd::loadDatasetEmbedding(folder, s.body.mesh.numFaces());
  EXPECT_EQ(embedding.triangle, s.embedding.triangle);
  EXPECT_EQ(embedding.barycentric, s.embedding.barycentric);
  EXPECT_EQ(pd::loadDatasetRestPositions(folder, s.garment.mesh.numVertices()), s.rest);
}

// The appendix statistics: per face, the extreme area ratios over the samples and how often the face passes through
// the garment. Sample 0 is the T-shirt as made (nothing passes through), sample 1 the same with one front vertex pushed
// through the back.
TEST(FaceStatistics, AreaRatiosAndSelfIntersectionsPerFace) {
  const Fixture& s = setup();
  const fs::path folder = freshDir("face_statistics");
  const Eigen::MatrixX3d& V = s.garment.mesh.V;
  // A vertex in the middle of the front (largest z at the chest's height), pushed back past the back panel.
  int pierced = -1;
  const double chest = V.col(1).minCoeff() + 0.6 * (V.col(1).maxCoeff() - V.col(1).minCoeff());
  for (int v = 0; v < V.rows(); ++v)
    if (std::abs(V(v, 0)) < 0.03 && std::abs(V(v, 1) - chest) < 0.03 && (pierced < 0 || V(v, 2) > V(pierced, 2)))
      pierced = v;
  ASSERT_GE(pierced, 0);
  {
    pd::DatasetWriter writer(folder, s.settings(2), s.body, s.garment, s.rest, s.embedding);
    for (int i = 0; i < 2; ++i) {
      pd::Sample sample = s.sample(i);
      sample.positions = V.cast<float>();
      if (i == 1) sample.positions(pierced, 2) -= 0.5f;
      writer.add(i, sample);
    }
    writer.finish();
  }
  const pd::FaceStatistics stats = pd::faceStatistics(pd::openDataset(pd::DatasetFolder{folder}));
  const int faces = s.garment.mesh.numFaces();
  ASSERT_EQ(stats.samples, 2);
  ASSERT_EQ(stats.minAreaRatio.size(), faces);
  ASSERT_EQ(stats.selfIntersection.size(), faces);
  EXPECT_EQ(stats.samplesSelfIntersecting, 1);
  const Eigen::VectorXd asMade = pc::areaRatios(V.cast<float>().cast<double>(), s.garment.mesh);  // as stored
  for (int f = 0; f < faces; ++f) {
    const bool around = (s.garment.mesh.F.row(f).array() == pierced).any();
    if (around) EXPECT_EQ(stats.selfIntersection(f), 0.5) << "face " << f;
    EXPECT_LE(stats.selfIntersection(f), 0.5);
    EXPECT_NEAR(stats.minAreaRatio(f), asMade(f), 1e-5) << "face " << f;
    if (around)
      EXPECT_GT(stats.maxAreaRatio(f), 5 * asMade(f)) << "face " << f;  // stretched half a metre
    else
      EXPECT_NEAR(stats.maxAreaRatio(f), asMade(f), 1e-5) << "face " << f;
  }
  // The back faces it passes through count too.
  EXPECT_GT((stats.selfIntersection.array() > 0).count(), 6);
}

TEST(DatasetWriter, RefusesBadSamples) {
  const Fixture& s = setup();
  const fs::path folder = freshDir("dataset");
  pd::DatasetWriter writer(folder, s.settings(4), s.body, s.garment, s.rest, s.embedding);
  pd::Sample good = s.sample(0);
  EXPECT_NE(inputErrorOf([&] { writer.add(4, good); }).find("outside this shard"), std::string::npos);
  pd::Sample shortPose = good;
  shortPose.pose.conservativeResize(89);
  EXPECT_NE(inputErrorOf([&] { writer.add(0, shortPose); }).find("89 floats, expected 90"), std::string::npos);
  pd::Sample notRotation = good;
  notRotation.pose.setConstant(2.0f);
  EXPECT_NE(inputErrorOf([&] { writer.add(0, notRotation); }).find("pose"), std::string::npos);
  pd::Sample nan = good;
  nan.positions(17, 1) = std::nanf("");
  EXPECT_NE(inputErrorOf([&] { writer.add(0, nan); }).find("positions are not finite"), std::string::npos);
  pd::Sample fewVertices = good;
  fewVertices.offsets.conservativeResize(100, 3);
  EXPECT_NE(inputErrorOf([&] { writer.add(0, fewVertices); }).find("offsets 100"), std::string::npos);
  pd::Sample rejected = good;
  rejected.stats.rejection = pd::Rejection::TriangleGrew;
  EXPECT_NE(inputErrorOf([&] { writer.add(0, rejected); }).find("triangle_grew"), std::string::npos);
  writer.add(0, good);
  EXPECT_NE(inputErrorOf([&] { writer.add(0, good); }).find("already added"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { writer.finish(); }).find("3 samples are still pending (first: 1)"), std::string::npos);
}

TEST(DatasetWriter, ResumesAfterACrashAndGivesTheSameArrays) {
  const Fixture& s = setup();
  const fs::path reference = freshDir("reference"), folder = freshDir("resumed");
  const int n = 20;
  s.writeAll(reference, s.settings(n), 8);
  {
    pd::DatasetWriter writer(folder, s.settings(n), s.body, s.garment, s.rest, s.embedding, {8});
    for (int i = 0; i < 11; ++i) writer.add(i, s.sample(i));
    writer.countRejection(pd::Rejection::NotFinite);
  }  // killed before finish: one full chunk, the rest saved by the destructor
  // A chunk that was being written when the process died.
  {
    std::ofstream stray(folder / "partial" / "chunk_000099.bin.tmp-12345", std::ios::binary);
    stray << "half a chunk";
  }
  EXPECT_FALSE(fs::exists(folder / "manifest.json"));
  EXPECT_NE(inputErrorOf([&] { pd::readDatasetInfo(folder); }).find("not finished"), std::string::npos);
  {
    pd::DatasetWriter writer(folder, s.settings(n), s.body, s.garment, s.rest, s.embedding, {8});
    EXPECT_TRUE(writer.resumed());
    EXPECT_EQ(writer.done(), 11);
    const std::vector<int> pending = writer.pending();
    ASSERT_EQ(pending.size(), 9u);
    EXPECT_EQ(pending.front(), 11);
    for (int i : pending) writer.add(i, s.sample(i));
    writer.finish();
  }
  EXPECT_FALSE(hasTemporaries(folder));
  for (const char* file : {"poses.npy", "positions.npy", "offsets.npy", "split.npy"})
    EXPECT_EQ(pd::fileCrc32(folder / file), pd::fileCrc32(reference / file)) << file;
  EXPECT_EQ(pd::readDatasetInfo(folder).stats.rejected.at("not_finite"), 1);
  pd::checkDataset(folder);

  // Re-running a finished dataset: nothing pending, finish does nothing.
  pd::DatasetWriter again(folder, s.settings(n), s.body, s.garment, s.rest, s.embedding);
  EXPECT_TRUE(again.pending().empty());
  again.finish();
  pd::checkDataset(folder);
}

TEST(DatasetWriter, RefusesAFolderWithOtherSettingsOrOtherContents) {
  const Fixture& s = setup();
  const fs::path folder = freshDir("dataset");
  {
    pd::DatasetWriter writer(folder, s.settings(6, 1), s.body, s.garment, s.rest, s.embedding);
    writer.add(0, s.sample(0));
  }
  const std::string seed =
      inputErrorOf([&] { pd::DatasetWriter(folder, s.settings(6, 2), s.body, s.garment, s.rest, s.embedding); });
  EXPECT_NE(seed.find("'seed'"), std::string::npos) << seed;
  const std::string count =
      inputErrorOf([&] { pd::DatasetWriter(folder, s.settings(7, 1), s.body, s.garment, s.rest, s.embedding); });
  EXPECT_NE(count.find("'count'"), std::string::npos) << count;
  pd::DatasetSettings otherBody = s.settings(6, 1);
  otherBody.body["shape"] = 1;
  const std::string body =
      inputErrorOf([&] { pd::DatasetWriter(folder, otherBody, s.body, s.garment, s.rest, s.embedding); });
  EXPECT_NE(body.find("'body'"), std::string::npos) << body;
  // Same settings, another dressing: the stored offsets would not match.
  Eigen::MatrixX3d moved = s.rest;
  moved(0, 0) += 0.01;
  const std::string rest =
      inputErrorOf([&] { pd::DatasetWriter(folder, s.settings(6, 1), s.body, s.garment, moved, s.embedding); });
  EXPECT_NE(rest.find("rest_positions.npy"), std::string::npos) << rest;
  // The refusals changed nothing: it still resumes.
  pd::DatasetWriter writer(folder, s.settings(6, 1), s.body, s.garment, s.rest, s.embedding);
  EXPECT_EQ(writer.pending().size(), 5u);

  const fs::path other = freshDir("other");
  { std::ofstream(other / "notes.txt") << "mine"; }
  const std::string notDataset =
      inputErrorOf([&] { pd::DatasetWriter(other, s.settings(6, 1), s.body, s.garment, s.rest, s.embedding); });
  EXPECT_NE(notDataset.find("notes.txt"), std::string::npos) << notDataset;
}

TEST(DatasetMerge, ShardsMergeToTheUnshardedArrays) {
  const Fixture& s = setup();
  const int n = 10;
  const fs::path whole = freshDir("whole");
  s.writeAll(whole, s.settings(n));
  std::vector<fs::path> shards;
  for (int k : {2, 0, 1}) {  // any order
    shards.push_back(freshDir("shard" + std::to_string(k)));
    s.writeAll(shards.back(), s.settings(n, 7, {k, 3}));
    const pd::DatasetShard shard{k, 3};
    EXPECT_EQ(pd::readDatasetInfo(shards.back()).settings.rows(), shard.end(n) - shard.first(n));
    pd::checkDataset(shards.back());
  }
  const fs::path merged = freshDir("merged");
  fs::remove_all(merged);
  const pd::DatasetInfo info = pd::mergeDatasets(shards, merged);
  EXPECT_EQ(info.settings.rows(), n);
  EXPECT_EQ(info.settings.shard.count, 1);
  for (const char* file : {"poses.npy", "positions.npy", "offsets.npy", "split.npy"}) {
    EXPECT_EQ(pd::fileCrc32(merged / file), pd::fileCrc32(whole / file)) << file;
    EXPECT_EQ(manifestCrc(merged, file), manifestCrc(whole, file)) << file;
  }
  EXPECT_EQ(info.stats.accepted, n);
  EXPECT_EQ(info.stats.maxIterations, 19);
  pd::checkDataset(merged);

  // A gap, an overlap, a shard of another dataset, a damaged shard, a non-empty output.
  const std::string gap = inputErrorOf([&] { pd::mergeDatasets({shards[0], shards[1]}, freshDir("gap")); });
  EXPECT_NE(gap.find("are in no shard"), std::string::npos) << gap;
  const std::string overlap = inputErrorOf([&] {
    pd::mergeDatasets({shards[0], shards[1], shards[2], whole}, freshDir("overlap"));
  });
  EXPECT_NE(overlap.find("overlaps"), std::string::npos) << overlap;
  const fs::path otherSeed = freshDir("seed8");
  s.writeAll(otherSeed, s.settings(n, 8, {0, 3}));
  const std::string seed = inputErrorOf([&] {
    pd::mergeDatasets({otherSeed, shards[0], shards[2]}, freshDir("mixed"));
  });
  EXPECT_NE(seed.find("'seed'"), std::string::npos) << seed;
  const fs::path damaged = freshDir("damaged");
  copyFolder(shards[1], damaged);
  {
    std::fstream f(damaged / "positions.npy", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(1000);
    f.put('\x55');
  }
  const fs::path crcOut = freshDir("crc");
  const std::string crc = inputErrorOf([&] { pd::mergeDatasets({shards[0], damaged, shards[2]}, crcOut); });
  EXPECT_NE(crc.find("positions.npy: CRC-32"), std::string::npos) << crc;
  // Nothing half-written: the output folder is as it was (empty), and no staging folder is left beside it.
  EXPECT_TRUE(fs::is_empty(crcOut));
  for (const auto& entry : fs::directory_iterator(crcOut.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find("crc.merging-"), std::string::npos) << entry.path();
  // Into a folder that holds a dataset (the merge just made), or anything else: refused, naming what is there.
  const std::string used = inputErrorOf([&] { pd::mergeDatasets(shards, merged); });
  EXPECT_NE(used.find("holds a dataset (manifest.json)"), std::string::npos) << used;
  std::ofstream(crcOut / "notes.txt") << "mine";
  const std::string notEmpty = inputErrorOf([&] { pd::mergeDatasets(shards, crcOut); });
  EXPECT_NE(notEmpty.find("not empty"), std::string::npos) << notEmpty;
}

class DatasetCheck : public ::testing::Test {
 protected:
  static fs::path good() {
    static const fs::path folder = [] {
      const fs::path f =
          fs::temp_directory_path() / "pixelcloth-tests" / ("dataset-check-" + std::to_string(::getpid()));
      fs::remove_all(f);
      setup().writeAll(f, setup().settings(6));
      return f;
    }();
    return folder;
  }
  fs::path copy(const std::string& name) {
    const fs::path folder = freshDir(name);
    copyFolder(good(), folder);
    return folder;
  }
};

TEST_F(DatasetCheck, CatchesAFlippedByte) {
  const fs::path folder = copy("flipped");
  std::fstream f(folder / "offsets.npy", std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(500);
  const char c = static_cast<char>(f.get());
  f.seekp(500);
  f.put(static_cast<char>(c ^ 0x10));
  f.close();
  const std::string message = inputErrorOf([&] { pd::checkDataset(folder); });
  EXPECT_NE(message.find("offsets.npy: CRC-32"), std::string::npos) << message;
}

TEST_F(DatasetCheck, OpeningVerifiesEveryFileReadUnlessTurnedOff) {
  const fs::path folder = copy("opened");
  auto flip = [&](const fs::path& file, std::streamoff at) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(at);
    const char c = static_cast<char>(f.get());
    f.seekp(at);
    f.put(static_cast<char>(c ^ 0x10));
  };
  flip(folder / "offsets.npy", 500);
  std::string message = inputErrorOf([&] { pd::openDataset(folder); });
  EXPECT_NE(message.find((folder / "offsets.npy").string() + ": CRC-32"), std::string::npos) << message;
  EXPECT_NE(message.find("--no-verify"), std::string::npos) << message;
  const pd::DatasetFolder unchecked(folder, pd::Checksums::Skip);
  EXPECT_EQ(pd::openDataset(unchecked).rows(), 6);  // read as it is
  // The choice travels with what was read: the garment of a Skip folder's info is read unchecked too.
  std::ofstream(folder / "garment" / "garment.obj", std::ios::app) << "# edited by hand\n";
  EXPECT_EQ(pd::datasetGarment(pd::readDatasetInfo(unchecked)).mesh.numVertices(), setup().garment.mesh.numVertices());
  message = inputErrorOf([&] { pd::datasetGarment(pd::readDatasetInfo(folder)); });
  EXPECT_NE(message.find("garment.obj: "), std::string::npos) << message;
  EXPECT_NE(message.find("manifest.json says"), std::string::npos) << message;

  const fs::path other = copy("opened_body");
  flip(other / "body" / "weights.npy", 300);
  message = inputErrorOf([&] { pd::loadDatasetBody(other); });
  EXPECT_NE(message.find("weights.npy: CRC-32"), std::string::npos) << message;
  flip(other / "rest_positions.npy", 200);
  message = inputErrorOf([&] { pd::loadDatasetRestPositions(other, setup().garment.mesh.numVertices()); });
  EXPECT_NE(message.find("rest_positions.npy: CRC-32"), std::string::npos) << message;
}

TEST_F(DatasetCheck, CatchesAWrongShape) {
  const fs::path folder = copy("shape");
  pc::writeNpy(folder / "positions.npy", std::vector<float>(5 * 7 * 3, 0.0f), {5, 7, 3});
  updateChecksum(folder, "positions.npy");
  const std::string message = inputErrorOf([&] { pd::checkDataset(folder); });
  EXPECT_NE(message.find("positions.npy"), std::string::npos) << message;
  EXPECT_NE(message.find("(5, 7, 3)"), std::string::npos) << message;
  EXPECT_NE(inputErrorOf([&] { pd::openDataset(folder); }).find("positions.npy"), std::string::npos);
}

TEST_F(DatasetCheck, CatchesNaN) {
  const fs::path folder = copy("nan");
  pc::NpyArray offsets = pc::readNpy(folder / "offsets.npy");
  reinterpret_cast<float*>(offsets.bytes.data())[3 * 100 + 1] = std::nanf("");
  pc::writeNpy(folder / "offsets.npy", offsets);
  updateChecksum(folder, "offsets.npy");
  const std::string message = inputErrorOf([&] { pd::checkDataset(folder); });
  EXPECT_NE(message.find("offsets.npy: value nan at row 1, element 302 (counting from 1) is not finite"),
            std::string::npos)
      << message;
  // Opening it checks the values too, also without the checksums (--no-verify).
  for (const pd::Checksums checksums : {pd::Checksums::Verify, pd::Checksums::Skip})
    EXPECT_NE(inputErrorOf([&] {
                pd::openDataset(pd::DatasetFolder(folder, checksums));
              }).find("offsets.npy: value nan at row 1, element 302 (counting from 1) is not finite"),
              std::string::npos);
}

TEST_F(DatasetCheck, CatchesABadSplit) {
  const fs::path folder = copy("split");
  pc::writeNpy(folder / "split.npy", std::vector<std::uint8_t>{0, 0, 7, 0, 0, 1}, {6});
  updateChecksum(folder, "split.npy");
  const std::string message = inputErrorOf([&] { pd::checkDataset(folder); });
  EXPECT_NE(message.find("split.npy: row 3 has split value 7"), std::string::npos) << message;
}

TEST_F(DatasetCheck, CatchesOffsetsThatDoNotMatchPositions) {
  const fs::path folder = copy("offsets");
  pc::NpyArray offsets = pc::readNpy(folder / "offsets.npy");
  const std::int64_t rowFloats = offsets.shape[1] * 3;
  reinterpret_cast<float*>(offsets.bytes.data())[5 * rowFloats + 30] += 0.001f;  // the last sample is checked
  pc::writeNpy(folder / "offsets.npy", offsets);
  updateChecksum(folder, "offsets.npy");
  const std::string message = inputErrorOf([&] { pd::checkDataset(folder); });
  EXPECT_NE(message.find("offsets.npy: row 6"), std::string::npos) << message;
  EXPECT_NE(message.find("recomputed"), std::string::npos) << message;
}

TEST_F(DatasetCheck, CatchesAManifestThatDisagrees) {
  const fs::path folder = copy("manifest");
  nlohmann::json manifest = pc::readJson(folder / "manifest.json");
  manifest["vertex_count"] = 100;
  pc::writeJson(folder / "manifest.json", manifest);
  // The manifest disagrees with itself first: its declared arrays.
  const std::string declared = inputErrorOf([&] { pd::checkDataset(folder); });
  EXPECT_NE(declared.find("arrays: positions: shape"), std::string::npos) << declared;
  EXPECT_NE(declared.find("make it [6, 100, 3]"), std::string::npos) << declared;
  // Without them (a hand-made manifest), the arrays themselves disagree.
  manifest.erase("arrays");
  pc::writeJson(folder / "manifest.json", manifest);
  const std::string message = inputErrorOf([&] { pd::checkDataset(folder); });
  EXPECT_NE(message.find("positions.npy"), std::string::npos) << message;
  EXPECT_NE(message.find("100 vertices"), std::string::npos) << message;
  fs::remove(folder / "poses.npy");
  EXPECT_NE(inputErrorOf([&] { pd::checkDataset(folder); }).find("poses.npy: missing"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { pd::checkDataset(folder / "nowhere"); }).find("no such dataset folder"),
            std::string::npos);
}

TEST_F(DatasetCheck, CatchesAnotherFormatAndWrongDeclaredShapes) {
  const fs::path folder = copy("declared");
  const nlohmann::json good = pc::readJson(folder / "manifest.json");
  auto refusal = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json manifest = good;
    edit(manifest);
    pc::writeJson(folder / "manifest.json", manifest);
    return inputErrorOf([&] { pd::checkDataset(folder); });
  };
  EXPECT_NE(refusal([](nlohmann::json& m) {
              m["format"] = "pixelcloth.model";
            }).find("format 'pixelcloth.model', expected 'pixelcloth.dataset'"),
            std::string::npos);
  EXPECT_NE(refusal([](nlohmann::json& m) { m["format"] = 7; }).find("format"), std::string::npos);
  const std::string shape = refusal([](nlohmann::json& m) { m["arrays"]["offsets"]["shape"] = {6, 3}; });
  EXPECT_NE(shape.find("arrays: offsets: shape [6,3]"), std::string::npos) << shape;
  const std::string file = refusal([](nlohmann::json& m) { m["arrays"]["split"]["file"] = "../split.npy"; });
  EXPECT_NE(file.find("arrays: split: file '../split.npy', expected 'split.npy'"), std::string::npos) << file;
  EXPECT_NE(refusal([](nlohmann::json& m) { m["arrays"].erase("poses"); }).find("poses"), std::string::npos);
  // The manifest as written passes.
  pc::writeJson(folder / "manifest.json", good);
  EXPECT_EQ(pd::checkDataset(folder).rows, 6);
}

TEST_F(DatasetCheck, PythonsZlibAgreesWithTheChecksums) {
  if (std::system("python3 -c 'import zlib' 2>/dev/null") != 0) GTEST_SKIP() << "no python3";
  const fs::path folder = good();
  const fs::path script = freshDir("python") / "verify.py";
  std::ofstream(script) << "import json, sys, zlib, os\n"
                           "folder = sys.argv[1]\n"
                           "m = json.load(open(os.path.join(folder, 'manifest.json')))\n"
                           "for name, entry in m['checksums'].items():\n"
                           "    data = open(os.path.join(folder, name), 'rb').read()\n"
                           "    assert zlib.crc32(data) == entry['crc32'], name\n"
                           "    assert len(data) == entry['bytes'], name\n"
                           "try:\n"
                           "    import numpy\n"
                           "except ImportError:\n"
                           "    sys.exit(0)\n"
                           "p = numpy.load(os.path.join(folder, 'poses.npy'))\n"
                           "x = numpy.load(os.path.join(folder, 'positions.npy'))\n"
                           "s = numpy.load(os.path.join(folder, 'split.npy'))\n"
                           "assert p.shape == (m['rows'], 90) and p.dtype == numpy.float32\n"
                           "assert x.shape == (m['rows'], m['vertex_count'], 3)\n"
                           "assert s.dtype == numpy.uint8 and (s == 0).sum() == m['counts']['train']\n";
  const std::string command = "python3 " + script.string() + " " + folder.string();
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(DatasetImport, ReadsPoseFilesInEveryForm) {
  const fs::path dir = freshDir("poses");
  const Eigen::VectorXf a = pb::randomPose(1, 0.5).toVector(), b = pb::randomPose(2, 0.5).toVector();
  {
    std::ofstream csv(dir / "poses.csv");
    for (int k = 0; k < 90; ++k) csv << (k ? "," : "") << "r" << k;
    csv << "\n";
    for (const Eigen::VectorXf* p : {&a, &b}) {
      for (int k = 0; k < 90; ++k) csv << (k ? "," : "") << (*p)[k];
      csv << "\n";
    }
  }
  std::vector<Eigen::VectorXf> poses = pd::readPoseSequence(dir / "poses.csv", 90);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_LT((poses[1] - b).norm(), 1e-5);
  nlohmann::json list = nlohmann::json::array();
  list.push_back(std::vector<float>(a.data(), a.data() + 90));
  list.push_back({{"joints", {{"l_arm", {{"euler_deg", {0, 30, 10}}}}}}});
  pc::writeJson(dir / "poses.json", {{"poses", list}});
  poses = pd::readPoseSequence(dir / "poses.json", 90);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0], a);
  // The necktie reads the first four joints.
  EXPECT_EQ(pd::readPoseSequence(dir / "poses.json", 36)[0], a.head(36));

  {
    std::ofstream csv(dir / "short.csv");
    for (int k = 0; k < 89; ++k) csv << (k ? "," : "") << a[k];
    csv << "\n";
  }
  const std::string columns = inputErrorOf([&] { pd::readPoseSequence(dir / "short.csv", 90); });
  EXPECT_NE(columns.find("short.csv: line 1: 89 columns, expected 90"), std::string::npos) << columns;
  pc::writeJson(dir / "twos.json", nlohmann::json::array({std::vector<float>(90, 2.0f)}));
  EXPECT_NE(inputErrorOf([&] { pd::readPoseSequence(dir / "twos.json", 90); }).find("twos.json: pose 0"),
            std::string::npos);

  // A pose beyond the joint limits (a forearm bent about z, as motion capture has) is refused, or clamped when asked.
  nlohmann::json beyond = nlohmann::json::array();
  beyond.push_back(std::vector<float>(a.data(), a.data() + 90));
  beyond.push_back({{"joints", {{"l_forearm", {{"euler_deg", {0, -30, 29}}}}}}});
  pc::writeJson(dir / "beyond.json", beyond);
  const std::string refused = inputErrorOf([&] { pd::readPoseSequence(dir / "beyond.json", 90); });
  EXPECT_NE(refused.find("beyond.json: pose 1: joint 'l_forearm': z = 29"), std::string::npos) << refused;
  EXPECT_NE(refused.find("--clamp-to-limits"), std::string::npos) << refused;
  poses = pd::readPoseSequence(dir / "beyond.json", 90, pb::BeyondLimits::Clamp);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0], a);
  const Eigen::Matrix<double, 10, 3> clamped = pb::Pose::fromVector(poses[1]).toEulerDegrees();
  EXPECT_NEAR(clamped(6, 2), 0, 1e-4);
  EXPECT_NEAR(clamped(6, 1), -30, 1e-3);
}

TEST(DatasetImport, ImportsAnObjSequenceWithPoses) {
  const Fixture& s = setup();
  const fs::path dir = freshDir("import"), objs = dir / "objs", out = dir / "dataset";
  const int n = 4;
  std::ofstream csv(dir / "poses.csv");
  for (int i = 0; i < n; ++i) {
    const pd::Sample sample = s.sample(i);
    pc::Mesh mesh = s.garment.mesh;
    mesh.V = sample.positions.cast<double>();
    pc::writeMesh(objs / ("frame_" + std::to_string(i * 5) + ".obj"), mesh);  // frame_0, _5, _10, _15
    for (int k = 0; k < 90; ++k) csv << (k ? "," : "") << sample.pose[k];
    csv << "\n";
  }
  csv.close();
  const std::vector<fs::path> files = pd::objSequence(objs);
  ASSERT_EQ(files.size(), static_cast<size_t>(n));
  EXPECT_EQ(files[2].filename(), "frame_10.obj");
  pd::importDataset(files, dir / "poses.csv", s.body, s.garment, s.rest, s.embedding, out,
                    {{{"kind", "mannequin"}}, 3});
  const pd::DatasetCheckReport report = pd::checkDataset(out, {n, 2e-5});
  EXPECT_EQ(report.strongSamples, n);
  const pd::Dataset d = pd::openDataset(out);
  EXPECT_EQ(d.info.settings.source, "imported");
  for (int i = 0; i < n; ++i) EXPECT_LT((d.offsetsOf(i) - s.sample(i).offsets).cwiseAbs().maxCoeff(), 1e-5) << i;
  EXPECT_GT(d.info.stats.minAreaRatio, 0.05);  // measured on the imported frames (the fixture's coarse body: 0.07)

  // A frame of another garment, and fewer poses than frames.
  pc::Mesh small = s.garment.mesh;
  small.V = small.V.topRows(100).eval();
  small.F.resize(1, 3);
  small.F << 0, 1, 2;
  small.UV.resize(0, 2);
  small.FUV.resize(0, 3);
  pc::writeMesh(objs / "frame_20.obj", small);
  std::vector<fs::path> withSmall = pd::objSequence(objs);
  const std::string vertices = inputErrorOf(
      [&] { pd::importDataset(withSmall, dir / "poses.csv", s.body, s.garment, s.rest, s.embedding, dir / "bad"); });
  EXPECT_NE(vertices.find("poses for 5 OBJ"), std::string::npos) << vertices;
  withSmall.erase(withSmall.begin());
  const std::string topology = inputErrorOf(
      [&] { pd::importDataset(withSmall, dir / "poses.csv", s.body, s.garment, s.rest, s.embedding, dir / "bad"); });
  EXPECT_NE(topology.find("frame_20.obj: 100 vertices"), std::string::npos) << topology;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}
