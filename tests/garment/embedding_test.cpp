// Cloth pixels embedded in the body, and offsets in their local frames (DESIGN.md "Offsets").
#include "pixelcloth/garment/embedding.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/error.h"
#include "support/fixtures.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pg = pixelcloth::garment;

using pixelcloth::testing::coarseMannequin;

namespace {

/// Points 0-3 cm off the body near random body vertices, with u-directions tangent to the body there.
struct Cloud {
  Eigen::MatrixX3d points, uDirections;
};
Cloud cloudAroundBody(int count) {
  const pb::Body& body = coarseMannequin();
  Eigen::MatrixX3d normals = pc::vertexNormals(body.mesh.V, body.mesh.F);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> vertex(0, body.mesh.numVertices() - 1);
  std::uniform_real_distribution<double> height(0.0, 0.03);
  Cloud cloud{Eigen::MatrixX3d(count, 3), Eigen::MatrixX3d(count, 3)};
  for (int i = 0; i < count; ++i) {
    int v = vertex(rng);
    Eigen::Vector3d n = normals.row(v);
    cloud.points.row(i) = body.mesh.V.row(v) + height(rng) * n.transpose();
    cloud.uDirections.row(i) = n.cross(Eigen::Vector3d(0.3, 0.5, 0.8)).normalized().transpose();
  }
  return cloud;
}
}  // namespace

TEST(Embedding, FramesAreOrthonormalAndOffsetsRoundTripOnRestAndPosedBodies) {
  const pb::Body& body = coarseMannequin();
  Cloud cloud = cloudAroundBody(500);
  pg::Embedding embedding = pg::embedClosest(body.mesh.V, body.mesh.F, cloud.points, cloud.uDirections);
  EXPECT_NO_THROW(embedding.validate(body.mesh.numFaces()));
  for (const Eigen::MatrixX3d& V : {body.mesh.V, body.posedVertices(pb::randomPose(3))}) {
    pg::EmbeddedFrames frames = pg::embeddedFrames(V, body.mesh.F, embedding);
    for (int i = 0; i < embedding.size(); ++i) {
      EXPECT_NEAR(frames.t.row(i).norm(), 1.0, 1e-12);
      EXPECT_NEAR(frames.n.row(i).norm(), 1.0, 1e-12);
      EXPECT_NEAR(frames.t.row(i).dot(frames.n.row(i)), 0.0, 1e-12);
      EXPECT_LT((frames.b.row(i) - frames.n.row(i).cross(frames.t.row(i))).norm(), 1e-12);
    }
    Eigen::MatrixX3d offsets = pg::offsetsFromPositions(frames, cloud.points);
    EXPECT_LT((pg::positionsFromOffsets(frames, offsets) - cloud.points).cwiseAbs().maxCoeff(), 1e-12);
  }
  // On the rest body, a point off the surface sits mostly along the normal: dn carries most of its offset.
  pg::EmbeddedFrames rest = pg::embeddedFrames(body.mesh.V, body.mesh.F, embedding);
  Eigen::MatrixX3d offsets = pg::offsetsFromPositions(rest, cloud.points);
  EXPECT_GT(offsets.col(2).mean(), 0.01);
  EXPECT_GT(offsets.col(2).minCoeff(), -0.005);
}

TEST(Embedding, OffsetsAreInvariantUnderRigidMotionAndFollowThePose) {
  const pb::Body& body = coarseMannequin();
  Cloud cloud = cloudAroundBody(300);
  pg::Embedding embedding = pg::embedClosest(body.mesh.V, body.mesh.F, cloud.points, cloud.uDirections);
  Eigen::MatrixX3d offsets =
      pg::offsetsFromPositions(pg::embeddedFrames(body.mesh.V, body.mesh.F, embedding), cloud.points);

  Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 1, 0.3).normalized()).toRotationMatrix();
  Eigen::RowVector3d shift(0.4, -0.1, 2.0);
  Eigen::MatrixX3d movedBody = (body.mesh.V * r.transpose()).rowwise() + shift;
  Eigen::MatrixX3d movedPoints = (cloud.points * r.transpose()).rowwise() + shift;
  Eigen::MatrixX3d movedOffsets =
      pg::offsetsFromPositions(pg::embeddedFrames(movedBody, body.mesh.F, embedding), movedPoints);
  EXPECT_LT((movedOffsets - offsets).cwiseAbs().maxCoeff(), 1e-9);

  // Fixed offsets on a posed body: points near the left hand move with it.
  Eigen::Matrix<double, 10, 3> degrees = Eigen::Matrix<double, 10, 3>::Zero();
  degrees(5, 2) = -60;
  Eigen::MatrixX3d posed = pg::positionsFromOffsets(
      pg::embeddedFrames(body.posedVertices(pb::Pose::fromEulerDegrees(degrees)), body.mesh.F, embedding), offsets);
  for (int i = 0; i < cloud.points.rows(); ++i) {
    double moved = (posed.row(i) - cloud.points.row(i)).norm();
    if (cloud.points(i, 0) > 0.7) {
      EXPECT_GT(moved, 0.3) << i;
    }
    if (cloud.points(i, 0) < -0.1) {
      EXPECT_LT(moved, 1e-9) << i;
    }
  }
}

TEST(Embedding, BadEmbeddingsAreRefused) {
  const pb::Body& body = coarseMannequin();
  Cloud cloud = cloudAroundBody(10);
  pg::Embedding embedding = pg::embedClosest(body.mesh.V, body.mesh.F, cloud.points, cloud.uDirections);
  pg::Embedding outOfRange = embedding;
  outOfRange.triangle[3] = body.mesh.numFaces() + 5;
  EXPECT_THROW(outOfRange.validate(body.mesh.numFaces(), "embedding.npy"), pc::InputError);
  pg::Embedding notNormalised = embedding;
  notNormalised.barycentric(2, 0) += 0.5;
  EXPECT_THROW(pg::embeddedFrames(body.mesh.V, body.mesh.F, notNormalised), pc::InputError);
  EXPECT_THROW(pg::embedClosest(body.mesh.V, body.mesh.F, cloud.points, cloud.uDirections.topRows(3)), pc::InputError);
  // A u-direction along the normal of the triangle the point lands on has no tangent part.
  Eigen::MatrixX3d faceNormal = pc::faceNormals(body.mesh.V, body.mesh.F).row(embedding.triangle[0]);
  EXPECT_THROW(pg::embedClosest(body.mesh.V, body.mesh.F, cloud.points.topRows(1), faceNormal), pc::InputError);
}
