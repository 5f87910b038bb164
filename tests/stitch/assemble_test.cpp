#include "pixelcloth/stitch/assemble.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <set>

#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/patch.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace {

namespace ps = pixelcloth::stitch;
using pixelcloth::learn::NetworkPrediction;
using pixelcloth::testing::inputErrorOf;

/// Two overlapping "patches" on a 4-vertex garment: vertices 0-2 and 1-3, a batch of 2.
std::vector<NetworkPrediction> overlapping() {
  NetworkPrediction a{0, {0, 1, 2}, Eigen::MatrixXf(2, 9)}, b{1, {1, 2, 3}, Eigen::MatrixXf(2, 9)};
  for (int k = 0; k < 9; ++k) {
    a.values(0, k) = 1.0f + k;
    a.values(1, k) = -1.0f;
    b.values(0, k) = 10.0f + k;
    b.values(1, k) = 3.0f;
  }
  return {a, b};
}

TEST(Assemble, MeanOverTheNetworksThatPredictAVertex) {
  const Eigen::MatrixXf out = ps::assembleMean(overlapping(), 4);
  ASSERT_EQ(out.rows(), 2);
  ASSERT_EQ(out.cols(), 12);
  // Vertex 0 only in a, vertex 3 only in b, vertices 1 and 2 in both.
  EXPECT_FLOAT_EQ(out(0, 0), 1.0f);
  EXPECT_FLOAT_EQ(out(0, 3), 0.5f * (4.0f + 10.0f));  // a's vertex 1 is its 2nd, b's its 1st
  EXPECT_FLOAT_EQ(out(0, 8), 0.5f * (9.0f + 15.0f));
  EXPECT_FLOAT_EQ(out(0, 11), 18.0f);
  EXPECT_FLOAT_EQ(out(1, 4), 1.0f);  // the mean of -1 and 3
  EXPECT_FLOAT_EQ(out(1, 1), -1.0f);
  const Eigen::VectorXi count = ps::coverage(overlapping(), 4);
  EXPECT_EQ(count, (Eigen::VectorXi(4) << 1, 2, 2, 1).finished());
}

TEST(Assemble, RefusesAGarmentWithUncoveredVertices) {
  const std::string message = inputErrorOf([] { ps::assembleMean(overlapping(), 5); });
  EXPECT_NE(message.find("vertex 5"), std::string::npos) << message;  // the fifth, counted from 1
}

/// The T-shirt's 28 patch predictions of one sample, each patch's values the constant `value(patch id)` on every
/// vertex of its enlarged crop.
std::vector<NetworkPrediction> constantPatches(const std::function<float(int)>& value) {
  std::vector<NetworkPrediction> out;
  for (const pixelcloth::patches::Patch& patch : pixelcloth::patches::garmentPatches(pixelcloth::testing::tshirt())) {
    NetworkPrediction p;
    p.patch = patch.id;
    p.vertices = pixelcloth::patches::enlargedCrop(pixelcloth::testing::tshirt(), patch).sample.vertices;
    p.values = Eigen::MatrixXf::Constant(1, 3 * p.vertices.size(), value(patch.id));
    out.push_back(std::move(p));
  }
  return out;
}

TEST(Feather, WeightsAreOneOnThePatchAndFallToZeroAtTheCropsEdge) {
  const pixelcloth::garment::Garment& shirt = pixelcloth::testing::tshirt();
  const ps::FeatherAssembler feather(shirt);
  const std::vector<NetworkPrediction> predictions = constantPatches([](int) { return 0.0f; });
  const std::vector<pixelcloth::patches::Patch> patches = pixelcloth::patches::garmentPatches(shirt);
  for (size_t k = 0; k < predictions.size(); ++k) {
    const NetworkPrediction& p = predictions[k];
    const Eigen::VectorXf w = feather.weights(p);
    const std::set<int> own(patches[k].vertices.begin(), patches[k].vertices.end());
    ASSERT_GT(p.vertices.size(), own.size()) << "patch " << k << ": its crop holds its neighbours' vertices too";
    int between = 0;
    for (size_t i = 0; i < p.vertices.size(); ++i) {
      if (own.count(p.vertices[i])) {
        EXPECT_FLOAT_EQ(w(i), 1.0f);
      }
      EXPECT_GE(w(i), 0.0f);
      EXPECT_LE(w(i), 1.0f);
      between += w(i) > 0 && w(i) < 1;
    }
    EXPECT_GT(between, 0) << "patch " << k;
    EXPECT_FLOAT_EQ(w.minCoeff(), 0.0f) << "patch " << k << ": the farthest vertex of its crop";
  }
}

TEST(Feather, AgreeingPredictionsComeOutUnchangedAndEachPatchKeepsItsOwnInterior) {
  const pixelcloth::garment::Garment& shirt = pixelcloth::testing::tshirt();
  const ps::FeatherAssembler feather(shirt);
  const int V = shirt.mesh.numVertices();
  const Eigen::MatrixXf same = feather.assemble(constantPatches([](int) { return 0.25f; }));
  EXPECT_LT((same.array() - 0.25f).abs().maxCoeff(), 1e-6f);
  // Patch p predicts p: a vertex inside one patch and no other crop gets exactly its patch's value under both
  // assemblies; across a curve the feathered values stay between the two patches' values.
  const std::vector<NetworkPrediction> predictions = constantPatches([](int id) { return static_cast<float>(id); });
  const Eigen::MatrixXf feathered = feather.assemble(predictions), mean = ps::assembleMean(predictions, V);
  const Eigen::VectorXi count = ps::coverage(predictions, V);
  int alone = 0, shared = 0;
  for (int v = 0; v < V; ++v) {
    if (count(v) == 1) {
      ++alone;
      EXPECT_FLOAT_EQ(feathered(0, 3 * v), mean(0, 3 * v));
    } else {
      ++shared;
      float low = 1e9f, high = -1e9f;
      for (const NetworkPrediction& p : predictions)
        if (std::binary_search(p.vertices.begin(), p.vertices.end(), v)) {
          low = std::min(low, static_cast<float>(p.patch));
          high = std::max(high, static_cast<float>(p.patch));
        }
      EXPECT_GE(feathered(0, 3 * v), low - 1e-4f);
      EXPECT_LE(feathered(0, 3 * v), high + 1e-4f);
    }
  }
  EXPECT_GT(alone, 1000);
  EXPECT_GT(shared, 300);
  // A patch id the garment does not have.
  std::vector<NetworkPrediction> bad = predictions;
  bad[0].patch = 99;
  EXPECT_NE(inputErrorOf([&] { feather.assemble(bad); }).find("patch 99"), std::string::npos);
}

}  // namespace
