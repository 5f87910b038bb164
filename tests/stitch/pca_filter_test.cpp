// The PCA filter: the three ways of fitting agree, all components reproduce the training data, k beyond the rank and
// a filter of another dataset are refused, and a saved filter reloads exactly and notices a changed file.
#include "pixelcloth/stitch/pca_filter.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "support/fixtures.h"
#include "support/test_util.h"

namespace {

namespace ps = pixelcloth::stitch;
namespace pl = pixelcloth::learn;
using pixelcloth::testing::inputErrorOf;

/// A dataset as the trainer sees it, of `rows` smooth random garments of the built-in T-shirt (each a random mix of
/// 5 smooth fields, so the data has rank 5 about its mean), all in the train split.
pl::TrainingData smoothData(int rows, std::uint32_t crc, std::uint64_t seed = 1) {
  pl::TrainingData data;
  data.folder = "/datasets/smooth" + std::to_string(crc);
  data.manifestCrc = crc;
  data.garment = pixelcloth::testing::tshirt();
  data.space = pl::OffsetSpace::Local;
  const Eigen::MatrixXf base = pixelcloth::testing::smoothOffsets(data.garment);
  const Eigen::MatrixX3d& V = data.garment.mesh.V;
  std::mt19937_64 random(seed);
  std::normal_distribution<float> normal;
  for (int r = 0; r < rows; ++r) {
    Eigen::MatrixXf values = base;
    for (int k = 1; k <= 5; ++k) {
      const float a = 0.01f * normal(random);
      for (int v = 0; v < values.rows(); ++v)
        values.row(v) += a * Eigen::RowVector3f(std::sin(k * V(v, 0)), std::cos(k * V(v, 1)), std::sin(k * V(v, 2)));
    }
    data.values.push_back(values);
    data.train.push_back(r);
  }
  return data;
}

/// Row r of the data as the filter takes it: vertex-major, 3 #V.
Eigen::MatrixXf rowsOf(const pl::TrainingData& data) {
  const int V = data.garment.mesh.numVertices();
  Eigen::MatrixXf rows(data.rows(), 3 * V);
  for (int r = 0; r < data.rows(); ++r)
    for (int v = 0; v < V; ++v) rows.block<1, 3>(r, 3 * v) = data.values[r].row(v);
  return rows;
}

TEST(PcaFilter, AllComponentsAreTheIdentityOnTrainingDataForEveryMethod) {
  const pl::TrainingData data = smoothData(12, 7);
  const Eigen::MatrixXf rows = rowsOf(data);
  for (pl::PcaMethod method : {pl::PcaMethod::Svd, pl::PcaMethod::Gram, pl::PcaMethod::Randomized}) {
    SCOPED_TRACE(pl::pcaMethodName(method));
    const ps::PcaFilter filter = ps::PcaFilter::fit(data, 0, method);
    EXPECT_EQ(filter.rank(), 12);
    EXPECT_LT((filter.filter(rows, 12) - rows).cwiseAbs().maxCoeff(), 2e-5f);
    // The data spans 5 directions about its mean: 5 components already reproduce it, 2 do not.
    EXPECT_LT((filter.filter(rows, 5) - rows).cwiseAbs().maxCoeff(), 2e-5f);
    EXPECT_GT((filter.filter(rows, 2) - rows).cwiseAbs().maxCoeff(), 1e-4f);
    const Eigen::MatrixXf gram = filter.basis().components.topRows(5) * filter.basis().components.topRows(5).transpose();
    EXPECT_TRUE(gram.isApprox(Eigen::MatrixXf::Identity(5, 5), 1e-4f));
  }
  // The methods find the same leading components (signs normalised) and variances.
  const ps::PcaFilter svd = ps::PcaFilter::fit(data, 5, pl::PcaMethod::Svd),
                      gram = ps::PcaFilter::fit(data, 5, pl::PcaMethod::Gram),
                      randomized = ps::PcaFilter::fit(data, 5, pl::PcaMethod::Randomized);
  for (const ps::PcaFilter* other : {&gram, &randomized}) {
    EXPECT_LT((other->basis().components - svd.basis().components).cwiseAbs().maxCoeff(), 1e-3f);
    EXPECT_TRUE(other->basis().variance.isApprox(svd.basis().variance, 1e-3f));
  }
}

TEST(PcaFilter, KBeyondTheRankAndAFilterOfAnotherDatasetAreRefused) {
  const pl::TrainingData data = smoothData(6, 7), other = smoothData(6, 8, 2);
  const ps::PcaFilter filter = ps::PcaFilter::fit(data, 4);
  const std::string beyond = inputErrorOf([&] { filter.filter(rowsOf(data), 5); });
  EXPECT_NE(beyond.find("rank 4"), std::string::npos) << beyond;
  EXPECT_NE(inputErrorOf([&] { filter.filter(rowsOf(data), 0); }).find("expected k from 1 to 4"), std::string::npos);
  filter.checkMatches(data);
  const std::string foreign = inputErrorOf([&] { filter.checkMatches(other); });
  EXPECT_NE(foreign.find("/datasets/smooth7"), std::string::npos) << foreign;
  EXPECT_NE(foreign.find("/datasets/smooth8"), std::string::npos) << foreign;
  EXPECT_NE(inputErrorOf([&] { filter.checkMatches("tshirt", data.garment.mesh.numVertices(), pl::OffsetSpace::Root); }).find("space local"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { ps::PcaFilter::fit(data, 7); }).find("expected 1 to 6"), std::string::npos);
}

TEST(PcaFilter, ASavedFilterReloadsExactlyAndAChangedFileIsRefused) {
  const pl::TrainingData data = smoothData(6, 7);
  const ps::PcaFilter filter = ps::PcaFilter::fit(data, 3);
  const std::filesystem::path folder = pixelcloth::testing::freshDir("pca") / "filter";
  filter.save(folder);
  const ps::PcaFilter loaded = ps::PcaFilter::load(folder);
  EXPECT_EQ(loaded.rank(), 3);
  EXPECT_EQ(loaded.basis().components, filter.basis().components);
  EXPECT_EQ(loaded.basis().mean, filter.basis().mean);
  EXPECT_EQ(loaded.info()["dataset_manifest_crc32"], 7);
  loaded.checkMatches(data);
  // One byte of the components changed: the checksum in pca.json catches it.
  {
    std::fstream f(folder / "components.npy", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(200);
    f.put('\x7f');
  }
  const std::string changed = inputErrorOf([&] { ps::PcaFilter::load(folder); });
  EXPECT_NE(changed.find("components.npy"), std::string::npos) << changed;
  EXPECT_NE(changed.find("CRC-32"), std::string::npos) << changed;
  std::filesystem::remove(folder / "pca.json");
  EXPECT_NE(inputErrorOf([&] { ps::PcaFilter::load(folder); }).find("pca.json"), std::string::npos);
}

}  // namespace
