// Embedding arrays on disk.
#include <gtest/gtest.h>

#include "fixtures.h"
#include "pixelcloth/core/embedding.h"
#include "pixelcloth/core/npy.h"
#include "test_util.h"

namespace pc = pixelcloth::core;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

TEST(EmbeddingIo, RoundTripsAndRefusesBadArrays) {
  const pc::Body& body = pixelcloth::testing::coarseMannequin();
  Eigen::MatrixX3d points = body.mesh.V.topRows(50) * 1.01;
  Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(50, 3);
  const Eigen::MatrixX3d normals = pc::vertexNormals(body.mesh.V, body.mesh.F);
  for (int i = 0; i < 50; ++i)
    u.row(i) = std::abs(normals(i, 0)) < 0.8 ? Eigen::RowVector3d(1, 0, 0) : Eigen::RowVector3d(0, 1, 0);
  const pc::Embedding embedding = pc::embedClosest(body.mesh.V, body.mesh.F, points, u);
  const auto dir = freshDir("embedding");
  pc::saveEmbedding(dir, embedding);
  const pc::Embedding back = pc::loadEmbedding(dir, body.mesh.numFaces());
  EXPECT_EQ(back.triangle, embedding.triangle);
  EXPECT_EQ(back.barycentric, embedding.barycentric);
  EXPECT_EQ(back.tangentCoords, embedding.tangentCoords);
  // Too few body faces for the stored triangles; a barycentric array of another length.
  EXPECT_NE(inputErrorOf([&] { pc::loadEmbedding(dir, 1); }).find("body face"), std::string::npos);
  pc::writeNpy(dir / "embedding_barycentric.npy", Eigen::MatrixXd(Eigen::MatrixXd::Zero(49, 3)));
  EXPECT_NE(inputErrorOf([&] { pc::loadEmbedding(dir); }).find("embedding_barycentric.npy"), std::string::npos);
}
