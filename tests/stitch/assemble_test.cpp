#include "pixelcloth/stitch/assemble.h"

#include <gtest/gtest.h>

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
  EXPECT_NE(message.find("vertex 4"), std::string::npos) << message;
}

}  // namespace
