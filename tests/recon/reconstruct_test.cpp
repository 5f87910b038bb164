// The posed body of a reconstruction: rebuilt vertices inside the body, or nearer it than the clearance, are moved
// out along its normal; the others stay.
#include "pixelcloth/recon/reconstruct.h"

#include <gtest/gtest.h>

#include "support/fixtures.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/core/mesh.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pg = pixelcloth::garment;
namespace pr = pixelcloth::recon;

TEST(PosedBody, PushesPointsInsideOutToTheClearanceAndLeavesTheOthers) {
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  const pb::Pose pose = pb::Pose::identity();
  const Eigen::MatrixX3d V = body.posedVertices(pose);
  const Eigen::MatrixX3d N = pc::vertexNormals(V, body.mesh.F);
  const pr::PosedBody posed(V, body.mesh.F, pg::EmbeddedFrames{});
  // Every 10th body vertex, 5 mm inside and 5 cm outside.
  std::vector<int> picked;
  for (int v = 0; v < V.rows(); v += 10) picked.push_back(v);
  const int n = static_cast<int>(picked.size());
  Eigen::MatrixX3d inside(n, 3), outside(n, 3);
  for (int i = 0; i < n; ++i) {
    inside.row(i) = V.row(picked[i]) - 0.005 * N.row(picked[i]);
    outside.row(i) = V.row(picked[i]) + 0.05 * N.row(picked[i]);
  }
  const double clearance = 0.001;
  Eigen::MatrixX3d moved = inside;
  EXPECT_EQ(posed.pushOut(moved, clearance), n);
  int near = 0;
  for (int i = 0; i < n; ++i) {
    // Out along about the normal it went in by: 1 mm outside its vertex (the surface curves a little between
    // vertices 2 cm apart).
    const Eigen::RowVector3d target = V.row(picked[i]) + clearance * N.row(picked[i]);
    near += (moved.row(i) - target).norm() < 0.002 ? 1 : 0;
    EXPECT_GT((moved.row(i) - V.row(picked[i])).dot(N.row(picked[i])), -0.001) << picked[i];
  }
  EXPECT_GT(near, 0.9 * n);
  // Where they went is clear of the body: a second push hardly moves them (in a crease, where a point pushed off one
  // side comes near the other, by at most about the clearance).
  Eigen::MatrixX3d again = moved;
  posed.pushOut(again, clearance);
  const Eigen::VectorXd second = (again - moved).rowwise().norm();
  EXPECT_LT(second.maxCoeff(), 1.5 * clearance);
  EXPECT_LT((second.array() > 1e-4).count(), 0.02 * n);
  Eigen::MatrixX3d far = outside;
  EXPECT_EQ(posed.pushOut(far, clearance), 0);
  EXPECT_EQ(far, outside);
}
