// Embedding arrays on disk.
#include <gtest/gtest.h>

#include "pixelcloth/core/npy.h"
#include "pixelcloth/garment/embedding.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pg = pixelcloth::garment;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

TEST(EmbeddingIo, RoundTripsAndRefusesBadArrays) {
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  Eigen::MatrixX3d points = body.mesh.V.topRows(50) * 1.01;
  Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(50, 3);
  const Eigen::MatrixX3d normals = pc::vertexNormals(body.mesh.V, body.mesh.F);
  for (int i = 0; i < 50; ++i)
    u.row(i) = std::abs(normals(i, 0)) < 0.8 ? Eigen::RowVector3d(1, 0, 0) : Eigen::RowVector3d(0, 1, 0);
  const pg::Embedding embedding = pg::embedClosest(body.mesh.V, body.mesh.F, points, u);
  const auto dir = freshDir("embedding");
  pg::saveEmbedding(dir, embedding);
  const pg::Embedding back = pg::loadEmbedding(dir, body.mesh.numFaces());
  EXPECT_EQ(back.triangle, embedding.triangle);
  EXPECT_EQ(back.barycentric, embedding.barycentric);
  EXPECT_EQ(back.tangentCoords, embedding.tangentCoords);
  // Too few body faces for the stored triangles; a barycentric array of another length.
  EXPECT_NE(inputErrorOf([&] { pg::loadEmbedding(dir, 1); }).find("body face"), std::string::npos);
  pc::writeNpy(dir / "embedding_barycentric.npy", Eigen::MatrixXd(Eigen::MatrixXd::Zero(49, 3)));
  EXPECT_NE(inputErrorOf([&] { pg::loadEmbedding(dir); }).find("embedding_barycentric.npy"), std::string::npos);
}
