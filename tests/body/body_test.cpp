// The built-in mannequin, its skeleton and weights, skinning, joint limits, collision parts, import.
#include "pixelcloth/body/body.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>

#include "pixelcloth/core/error.h"
#include "support/body_fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;

using pixelcloth::testing::mannequin;

namespace {

Eigen::Vector3d column(const pb::Body& body, int v) { return body.mesh.V.row(v).transpose(); }

/// Fraction of triangles whose posed normal points against the normal carried rigidly by the
/// triangle's dominant joint: a flipped (inverted) triangle.
double flippedFraction(const pb::Body& body, const pb::Pose& pose) {
  Eigen::MatrixX3d posed = body.posedVertices(pose);
  pb::JointTransforms transforms = pb::forwardKinematics(body.skeleton, pose);
  Eigen::MatrixX3d restNormals = pc::faceNormals(body.mesh.V, body.mesh.F);
  Eigen::MatrixX3d posedNormals = pc::faceNormals(posed, body.mesh.F);
  int flipped = 0;
  for (int f = 0; f < body.mesh.numFaces(); ++f) {
    Eigen::RowVectorXd w = (body.weights.row(body.mesh.F(f, 0)) + body.weights.row(body.mesh.F(f, 1)) +
                            body.weights.row(body.mesh.F(f, 2)));
    Eigen::Index j;
    w.maxCoeff(&j);
    Eigen::Vector3d expected = transforms.rotations[j] * restNormals.row(f).transpose();
    if (posedNormals.row(f).dot(expected) < 0) ++flipped;
  }
  return static_cast<double>(flipped) / body.mesh.numFaces();
}

}  // namespace

TEST(Mannequin, ClosedManifoldSmoothAndLifeSized) {
  const pb::Body& body = mannequin();
  pc::TopologyReport topology = pc::checkTopology(body.mesh.numVertices(), body.mesh.F);
  EXPECT_TRUE(topology.closedManifold()) << topology.firstProblem;
  EXPECT_EQ(topology.components, 1);
  EXPECT_EQ(topology.isolatedVertices, 0);
  EXPECT_GE(body.mesh.numVertices(), 10000);
  EXPECT_LE(body.mesh.numVertices(), 20000);
  EXPECT_GT(pc::enclosedVolume(body.mesh.V, body.mesh.F), 0.0);
  EXPECT_NEAR(body.mesh.V.col(1).maxCoeff(), 1.75, 0.01);  // top of the head
  EXPECT_LT(body.mesh.V.col(1).minCoeff(), 0.8);           // torso reaches the hips
  EXPECT_GT(body.mesh.V.col(0).maxCoeff(), 0.85);          // hands in the T-pose
  EXPECT_LT(body.mesh.V.col(0).minCoeff(), -0.85);
  // Smooth: the angle between neighbouring face normals stays small. Measured on the default mannequin:
  // p99 ~17 degrees overall; away from the hands (|x| < 0.7 m) p99 ~13.5 and max ~22 degrees; the flat
  // hands' rims reach ~51 degrees.
  Eigen::MatrixX3d normals = pc::faceNormals(body.mesh.V, body.mesh.F);
  std::map<std::pair<int, int>, int> edgeFace;
  std::vector<double> angles;
  double worstAwayFromHands = 0, worst = 0;
  for (int f = 0; f < body.mesh.numFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      int a = body.mesh.F(f, k), b = body.mesh.F(f, (k + 1) % 3);
      auto [it, inserted] = edgeFace.emplace(std::minmax(a, b), f);
      if (inserted) continue;
      double angle = std::acos(std::clamp(normals.row(f).dot(normals.row(it->second)), -1.0, 1.0)) * 180 / M_PI;
      angles.push_back(angle);
      worst = std::max(worst, angle);
      if (std::abs(body.mesh.V(a, 0)) < 0.7) worstAwayFromHands = std::max(worstAwayFromHands, angle);
    }
  }
  std::sort(angles.begin(), angles.end());
  EXPECT_LT(angles[angles.size() * 99 / 100], 20.0);
  EXPECT_LT(worstAwayFromHands, 30.0);
  EXPECT_LT(worst, 60.0);
}

TEST(Mannequin, Deterministic) {
  pb::MannequinOptions coarse;
  coarse.edgeLength = 0.02;
  pb::Body a = pb::makeMannequin(coarse), b = pb::makeMannequin(coarse);
  EXPECT_EQ(a.mesh.V, b.mesh.V);
  EXPECT_EQ(a.mesh.F, b.mesh.F);
}

TEST(Mannequin, ShapeParameterChangesGirthNotHeight) {
  std::vector<double> volumes;
  for (double shape : {-1.0, 0.0, 2.0}) {
    pb::MannequinOptions options;
    options.shape = shape;
    options.edgeLength = 0.015;
    pb::Body body = pb::makeMannequin(options);
    EXPECT_TRUE(pc::checkTopology(body.mesh.numVertices(), body.mesh.F).closedManifold());
    EXPECT_NEAR(body.mesh.V.col(1).maxCoeff(), 1.75, 0.015);
    volumes.push_back(pc::enclosedVolume(body.mesh.V, body.mesh.F));
  }
  EXPECT_LT(volumes[0], 0.85 * volumes[1]);
  EXPECT_GT(volumes[2], 1.3 * volumes[1]);
  pb::MannequinOptions bad;
  bad.shape = 3;
  EXPECT_THROW(pb::makeMannequin(bad), pc::InputError);
}

TEST(SkinWeights, PartitionOfUnityNonNegativeAndSmooth) {
  const pb::Body& body = mannequin();
  ASSERT_EQ(body.weights.rows(), body.mesh.numVertices());
  ASSERT_EQ(body.weights.cols(), 12);
  EXPECT_GE(body.weights.minCoeff(), 0.0);
  EXPECT_LT((body.weights.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-9);
  // Smooth: weights change little across an edge (~7 mm long). Measured max ~0.19.
  double maxJump = 0;
  for (int f = 0; f < body.mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k) {
      int a = body.mesh.F(f, k), b = body.mesh.F(f, (k + 1) % 3);
      maxJump = std::max(maxJump, (body.weights.row(a) - body.weights.row(b)).cwiseAbs().maxCoeff());
    }
  EXPECT_LT(maxJump, 0.25);
  EXPECT_NO_THROW(body.validate());
}

TEST(SkinWeights, FollowTheNearestBone) {
  const pb::Body& body = mannequin();
  const pb::Skeleton& s = body.skeleton;
  for (int v = 0; v < body.mesh.numVertices(); ++v) {
    Eigen::Vector3d p = column(body, v);
    if (p.x() > 0.7) {
      EXPECT_GT(body.weights(v, s.index("l_forearm")), 0.95) << "hand vertex " << v;
    }
    if (p.x() < -0.7) {
      EXPECT_GT(body.weights(v, s.index("r_forearm")), 0.95) << "hand vertex " << v;
    }
    if (p.y() > 1.70) {
      EXPECT_GT(body.weights(v, s.index("head")), 0.85) << "head vertex " << v;
    }
    if (p.y() < 0.78) {
      EXPECT_GT(body.weights(v, s.index("root")), 0.8) << "pelvis vertex " << v;
    }
  }
}

TEST(Skinning, IdentityPoseReturnsTheRestMesh) {
  const pb::Body& body = mannequin();
  Eigen::MatrixX3d posed = body.posedVertices(pb::Pose::identity());
  EXPECT_LT((posed - body.mesh.V).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Skinning, ShoulderRotationMovesTheArmAndLeavesTheFarTorsoStill) {
  const pb::Body& body = mannequin();
  Eigen::Matrix<double, 10, 3> degrees = Eigen::Matrix<double, 10, 3>::Zero();
  degrees(5, 2) = -70;  // l_arm down towards the side
  Eigen::MatrixX3d posed = body.posedVertices(pb::Pose::fromEulerDegrees(degrees));
  double handMoved = 0, farMoved = 0;
  for (int v = 0; v < body.mesh.numVertices(); ++v) {
    double d = (posed.row(v) - body.mesh.V.row(v)).norm();
    if (body.mesh.V(v, 0) > 0.75) handMoved = std::max(handMoved, d);
    if (body.mesh.V(v, 0) < -0.08 && body.mesh.V(v, 1) < 1.35) farMoved = std::max(farMoved, d);
  }
  EXPECT_GT(handMoved, 0.5);
  EXPECT_LT(farMoved, 1e-9);
}

TEST(Skinning, ForwardKinematicsKeepsBoneLengthsAndTheRoot) {
  const pb::Skeleton s = pb::mannequinSkeleton();
  pb::Pose pose = pb::randomPose(7);
  pb::JointTransforms t = pb::forwardKinematics(s, pose);
  EXPECT_LT((t.positions.row(0) - s.positions.row(0)).norm(), 1e-12);
  for (int j = 1; j < s.numJoints(); ++j) {
    int p = s.parents[j];
    EXPECT_NEAR((t.positions.row(j) - t.positions.row(p)).norm(), (s.positions.row(j) - s.positions.row(p)).norm(),
                1e-12);
  }
}

TEST(Skinning, FewTrianglesFlipAcrossTheJointRanges) {
  // Every posable joint, every axis, at both ends of its range, then random poses inside the ranges.
  // Measured on the default mannequin: worst single-axis extreme ~0.3% of triangles (elbow fully
  // flexed, where linear blend skinning collapses the inner elbow), random poses ~0.1%.
  const pb::Body& body = mannequin();
  double worst = 0;
  for (int k = 0; k < 10; ++k) {
    const pb::JointLimits& limits = pb::jointLimits(pb::kPoseJoints[k]);
    for (int axis = 0; axis < 3; ++axis) {
      for (double bound : {limits.lower[axis], limits.upper[axis]}) {
        Eigen::Matrix<double, 10, 3> degrees = Eigen::Matrix<double, 10, 3>::Zero();
        degrees(k, axis) = bound;
        double fraction = flippedFraction(body, pb::Pose::fromEulerDegrees(degrees));
        worst = std::max(worst, fraction);
        EXPECT_LT(fraction, 0.01) << pb::kPoseJoints[k] << " axis " << axis << " at " << bound << " degrees";
      }
    }
  }
  double randomWorst = 0;
  for (int seed = 0; seed < 20; ++seed)
    randomWorst = std::max(randomWorst, flippedFraction(body, pb::randomPose(seed)));
  EXPECT_LT(randomWorst, 0.01);
  RecordProperty("worst_single_axis_flip_fraction", std::to_string(worst));
  RecordProperty("worst_random_flip_fraction", std::to_string(randomWorst));
}

TEST(Pose, EulerRoundTripAndVectorLayout) {
  for (int seed = 0; seed < 50; ++seed) {
    pb::Pose pose = pb::randomPose(seed);
    EXPECT_TRUE(pose.withinLimits(1e-6));
    Eigen::Matrix<double, 10, 3> degrees = pose.toEulerDegrees();
    pb::Pose again = pb::Pose::fromEulerDegrees(degrees);
    for (int k = 0; k < 10; ++k) EXPECT_LT((again.rotations[k] - pose.rotations[k]).norm(), 1e-9);
    pb::Pose fromFloats = pb::Pose::fromVector(pose.toVector());
    for (int k = 0; k < 10; ++k) EXPECT_LT((fromFloats.rotations[k] - pose.rotations[k]).norm(), 1e-6);
  }
  // Row-major blocks in pose-joint order.
  Eigen::Matrix<double, 10, 3> degrees = Eigen::Matrix<double, 10, 3>::Zero();
  degrees(5, 2) = 90;  // l_arm: z by 90 degrees
  Eigen::VectorXf v = pb::Pose::fromEulerDegrees(degrees).toVector();
  EXPECT_NEAR(v[45 + 1], -1.0f, 1e-6);  // R(0,1) of Rz(90) is -1
  EXPECT_NEAR(v[45 + 3], 1.0f, 1e-6);   // R(1,0) is +1
  EXPECT_FALSE(pb::Pose::fromEulerDegrees(degrees * 1.5).withinLimits());
}

TEST(Pose, BadVectorsAreRefused) {
  Eigen::VectorXf tooShort = Eigen::VectorXf::Zero(36);
  EXPECT_THROW(pb::Pose::fromVector(tooShort, "poses.npy"), pc::InputError);
  Eigen::VectorXf v = pb::Pose::identity().toVector();
  v[10] = std::numeric_limits<float>::quiet_NaN();
  try {
    pb::Pose::fromVector(v, "pose.json");
    FAIL();
  } catch (const pc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("spine"), std::string::npos) << e.what();
  }
  Eigen::VectorXf scaled = pb::Pose::identity().toVector() * 2.0f;
  EXPECT_THROW(pb::Pose::fromVector(scaled), pc::InputError);
}

TEST(Pose, LeadingJointsGiveTheRestAtIdentity) {
  // A necktie dataset's 36 floats: the first four joints; the arms stay at rest.
  pb::Pose bent = pb::Pose::identity();
  bent.rotations[1] = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const pb::Pose back = pb::Pose::fromLeading(bent.toVector().head(36), "poses.npy");
  EXPECT_TRUE(back.rotations[1].isApprox(bent.rotations[1], 1e-6));
  for (int k = 4; k < 10; ++k) EXPECT_TRUE(back.rotations[k].isIdentity(1e-12)) << k;
  EXPECT_TRUE(pb::Pose::fromLeading(Eigen::VectorXf(0)).rotations[0].isIdentity(1e-12));
  // Not whole joints, too many, not rotations: refused with the context.
  for (int size : {35, 99}) {
    const Eigen::VectorXf odd = Eigen::VectorXf::Zero(size);
    EXPECT_NE(pixelcloth::testing::inputErrorOf([&] { pb::Pose::fromLeading(odd, "poses.npy"); }).find("poses.npy"),
              std::string::npos)
        << size;
  }
  EXPECT_THROW(pb::Pose::fromLeading(Eigen::VectorXf::Zero(36)), pc::InputError);
}

TEST(JointLimits, EveryPosableJointHasSourcedLimitsAndTheRightMirrorsTheLeft) {
  for (const auto& name : pb::kPoseJoints) {
    const pb::JointLimits& l = pb::jointLimits(name);
    EXPECT_FALSE(l.source.empty());
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(l.lower[a], 0.0) << name;
      EXPECT_GE(l.upper[a], 0.0) << name;
    }
  }
  const pb::JointLimits& left = pb::jointLimits("l_arm");
  const pb::JointLimits& right = pb::jointLimits("r_arm");
  EXPECT_EQ(left.lower.x(), right.lower.x());
  EXPECT_EQ(left.upper.y(), -right.lower.y());
  EXPECT_EQ(left.upper.z(), -right.lower.z());
  EXPECT_THROW(pb::jointLimits("l_elbow"), pc::InputError);
}

TEST(SkinWeights, CorruptionMovesUpperArmWeightToTheTorso) {
  const pb::Body& body = mannequin();
  const pb::Skeleton& s = body.skeleton;
  for (std::string mode : {"torso", "torso+arm"}) {
    Eigen::MatrixXd w = pb::corruptUpperArmWeights(s, body.weights, mode, 0.5);
    EXPECT_LT((w.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-9);
    EXPECT_GE(w.minCoeff(), 0.0);
    Eigen::VectorXd left = body.weights.col(s.index("l_arm")), right = body.weights.col(s.index("r_arm"));
    Eigen::VectorXd torso = body.weights.col(s.index("spine1"));
    if (mode == "torso") {
      EXPECT_LT((w.col(s.index("l_arm")) - 0.5 * left).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT((w.col(s.index("spine1")) - torso - 0.5 * (left + right)).cwiseAbs().maxCoeff(), 1e-12);
    } else {
      EXPECT_LT((w.col(s.index("l_arm")) - 0.5 * left - 0.25 * right).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT((w.col(s.index("spine1")) - torso - 0.25 * (left + right)).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
  EXPECT_THROW(pb::corruptUpperArmWeights(s, body.weights, "legs"), pc::InputError);
}

TEST(CollisionParts, ThreeOverlappingPartsCoverTheBody) {
  const pb::Body& body = mannequin();
  ASSERT_EQ(body.parts.size(), 3u);
  EXPECT_EQ(body.parts[0].name, "left_arm");
  EXPECT_EQ(body.parts[1].name, "right_arm");
  EXPECT_EQ(body.parts[2].name, "torso");
  std::vector<int> count(body.mesh.numFaces(), 0);
  for (const auto& part : body.parts)
    for (int f : part.faces) ++count[f];
  EXPECT_EQ(*std::min_element(count.begin(), count.end()), 1);  // every face in some part
  int shared = 0;
  for (int c : count) shared += c > 1;
  EXPECT_GT(shared, 100);  // the parts overlap around the shoulders
  // Hands and elbows are in their arm only; the chest and belly are in the torso only.
  for (int f : body.parts[2].faces) EXPECT_LT(std::abs(body.mesh.V(body.mesh.F(f, 0), 0)), 0.35);
  for (int f : body.parts[0].faces) EXPECT_GT(body.mesh.V(body.mesh.F(f, 0), 0), 0.08);
  for (int f : body.parts[1].faces) EXPECT_LT(body.mesh.V(body.mesh.F(f, 0), 0), -0.08);
  // The torso meets both arms; the arms do not meet.
  const std::vector<std::vector<int>> meets = pb::meetingParts(body.parts);
  EXPECT_EQ(meets, (std::vector<std::vector<int>>{{2}, {2}, {0, 1}}));
}

// ---- import -----------------------------------------------------------------------------------------

namespace {
/// The mannequin with its arms lowered 40 degrees (an A-pose), and its joints there.
std::pair<pc::Mesh, pb::JointPositions> aPosedMannequin() {
  pb::Pose pose = pb::armsLowered(40);
  return {mannequin().posedMesh(pose), pb::posedJoints(mannequin(), pose)};
}
}  // namespace

TEST(Import, APoseBodyComesBackToTheTPose) {
  auto [mesh, joints] = aPosedMannequin();
  pb::Body imported = pb::importBody(mesh, joints, "apose.obj");
  EXPECT_NO_THROW(imported.validate());
  const pb::Body& original = mannequin();
  // Arms horizontal again: the imported elbow is level with the shoulder, and the surface is back.
  const pb::Skeleton& s = imported.skeleton;
  EXPECT_NEAR(s.positions(s.index("l_forearm"), 1), s.positions(s.index("l_arm"), 1), 1e-6);
  EXPECT_NEAR(s.positions(s.index("r_forearm"), 1), s.positions(s.index("r_arm"), 1), 1e-6);
  double meanError = (imported.mesh.V - original.mesh.V).rowwise().norm().mean();
  double maxHandError = 0;
  for (int v = 0; v < original.mesh.numVertices(); ++v)
    if (std::abs(original.mesh.V(v, 0)) > 0.6)
      maxHandError = std::max(maxHandError, (imported.mesh.V.row(v) - original.mesh.V.row(v)).norm());
  EXPECT_LT(meanError, 0.01);
  EXPECT_LT(maxHandError, 0.03);
  EXPECT_EQ(imported.parts.size(), 3u);
}

TEST(Import, OpenMeshIsRefusedWithAClearMessage) {
  auto [mesh, joints] = aPosedMannequin();
  pc::Mesh open = mesh;
  open.F = mesh.F.topRows(mesh.F.rows() - 5);
  try {
    pb::importBody(open, joints, "scan.obj");
    FAIL();
  } catch (const pc::InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("scan.obj"), std::string::npos) << message;
    EXPECT_NE(message.find("closed and manifold"), std::string::npos) << message;
    EXPECT_NE(message.find("boundary"), std::string::npos) << message;
  }
}

TEST(Import, ABodyInOtherUnitsIsRefusedWithTheUnitsItSeemsToBeIn) {
  auto [mesh, joints] = aPosedMannequin();
  mesh.V *= 100;  // centimetres
  for (auto& [name, p] : joints) p *= 100;
  const std::string message = pixelcloth::testing::inputErrorOf([&] { pb::importBody(mesh, joints, "scan.obj"); });
  EXPECT_NE(message.find("scan.obj: the body is 1"), std::string::npos) << message;
  EXPECT_NE(message.find("expected 0.5 to 2.5 metres"), std::string::npos) << message;
  EXPECT_NE(message.find("centimetres: scale it by 0.01"), std::string::npos) << message;
}

TEST(Import, ExtraShellsAreRefusedUnlessTheLargestComponentIsKept) {
  auto [mesh, joints] = aPosedMannequin();
  const int n = mesh.numVertices(), f = mesh.numFaces();
  // A closed tetrahedron beside the head, as a separately modelled eye would be.
  pc::Mesh eye = mesh;
  eye.V.conservativeResize(n + 4, 3);
  const Eigen::RowVector3d at = mesh.V.colwise().maxCoeff() - Eigen::RowVector3d(0.3, 0.1, 0.1);
  eye.V.bottomRows(4) << at, at + Eigen::RowVector3d(0.01, 0, 0), at + Eigen::RowVector3d(0, 0.01, 0),
      at + Eigen::RowVector3d(0, 0, 0.01);
  eye.F.conservativeResize(f + 4, 3);
  eye.F.bottomRows(4) << n, n + 2, n + 1, n, n + 1, n + 3, n, n + 3, n + 2, n + 1, n + 2, n + 3;
  std::string message = pixelcloth::testing::inputErrorOf([&] { pb::importBody(eye, joints, "scan.obj"); });
  EXPECT_NE(message.find("is closed but has 2 components"), std::string::npos) << message;
  EXPECT_NE(message.find("--largest-component"), std::string::npos) << message;

  // An open shell: the open edges are named on their component, vertices counted from 1.
  pc::Mesh open = eye;
  open.F.conservativeResize(f + 3, 3);
  message = pixelcloth::testing::inputErrorOf([&] { pb::importBody(open, joints, "scan.obj"); });
  EXPECT_NE(message.find("on component 2 of 2 (3 faces; the largest has " + std::to_string(f) + ")"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("--largest-component"), std::string::npos) << message;
  EXPECT_TRUE(message.find("(" + std::to_string(n + 1)) != std::string::npos ||
              message.find("(" + std::to_string(n + 2)) != std::string::npos ||
              message.find("(" + std::to_string(n + 3)) != std::string::npos)
      << "expected the shell's vertices " << n + 1 << " to " << n + 4 << ", counted from 1: " << message;

  pb::ImportOptions options;
  options.largestComponent = true;
  const pb::Body kept = pb::importBody(open, joints, "scan.obj", options);
  EXPECT_EQ(kept.mesh.numVertices(), n);
  EXPECT_EQ(kept.mesh.numFaces(), f);
}

TEST(Import, NonManifoldMeshIsRefused) {
  auto [mesh, joints] = aPosedMannequin();
  pc::Mesh bad = mesh;
  bad.F.conservativeResize(mesh.F.rows() + 1, 3);
  bad.F.row(mesh.F.rows()) << mesh.F(0, 0), mesh.F(0, 1), mesh.F(100, 2);  // a third face on an edge
  EXPECT_THROW(pb::importBody(bad, joints, "bad.obj"), pc::InputError);
}

TEST(Import, JointOutsideTheBodyIsNamed) {
  auto [mesh, joints] = aPosedMannequin();
  joints["l_forearm"] += Eigen::Vector3d(0, 0, 0.3);
  try {
    pb::importBody(mesh, joints, "body.obj");
    FAIL();
  } catch (const pc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'l_forearm'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside"), std::string::npos) << e.what();
  }
}

TEST(Import, JointFileErrors) {
  auto dir = pixelcloth::testing::freshDir("joints");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  auto expectMessage = [](const std::filesystem::path& path, const std::string& part) {
    try {
      pb::readJointPositions(path);
      FAIL() << path;
    } catch (const pc::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path.filename().string()), std::string::npos) << e.what();
    }
  };
  expectMessage(dir / "missing.json", "no such file");
  expectMessage(write("broken.json", "{\"joints\": {"), "broken.json");
  expectMessage(write("unknown.json", "{\"joints\": {\"l_elbow\": [0, 1, 0]}}"), "unknown joint 'l_elbow'");
  expectMessage(write("short.json", "{\"joints\": {\"neck\": [0, 1]}}"), "[x, y, z]");
  expectMessage(write("partial.json", "{\"joints\": {\"neck\": [0, 1.5, 0]}}"), "missing joint 'lower_back'");
  std::string allAtOne = "{\"joints\": {";
  for (const char* name : {"lower_back", "spine", "spine1", "neck", "l_shoulder", "l_arm", "l_forearm", "r_shoulder",
                           "r_arm", "r_forearm"})
    allAtOne += std::string(allAtOne.back() == '{' ? "" : ", ") + "\"" + name + "\": [0, 1, 0]";
  expectMessage(write("one_point.json", allAtOne + "}}"), "joints 'lower_back' and 'spine' are 0 mm apart");
}
