// Bone-heat skin weights, weight corruption and collision parts, on closed meshes.

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <memory>

#include "pixelcloth/body/body.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/mesh_index.h"

namespace pixelcloth::body {

using namespace core;

namespace {

/// Closest point parameter on segment [a, b].
Eigen::Vector3d closestOnSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Eigen::Vector3d ab = b - a;
  double len2 = ab.squaredNorm();
  double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

}  // namespace

void SkinWeightOptions::validate() const {
  PIXELCLOTH_CHECK(heatScale > 0 && std::isfinite(heatScale), "skin weights: heat scale must be positive");
  PIXELCLOTH_CHECK(minimumWeight >= 0 && minimumWeight < 0.1, "skin weights: minimum weight must be in [0, 0.1)");
}

Eigen::MatrixXd boneHeatWeights(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Skeleton& skeleton,
                                const SkinWeightOptions& options) {
  options.validate();
  const int nv = static_cast<int>(V.rows());
  const int nj = skeleton.numJoints();

  // Cotangent Laplacian L (negative semi-definite) and lumped (barycentric) mass M.
  const Eigen::SparseMatrix<double> laplacian = cotangentLaplacian(V, F);
  const Eigen::VectorXd mass = lumpedMass(V, F);

  // Nearest visible bone per vertex: a bone is visible when the segment from just inside the surface
  // to the bone's closest point does not cross the surface.
  const MeshIndex surface(V, F);
  Eigen::MatrixX3d normals = vertexNormals(V, F);
  Eigen::VectorXd heat = Eigen::VectorXd::Zero(nv);
  Eigen::MatrixXd nearest = Eigen::MatrixXd::Zero(nv, nj);
  std::vector<std::pair<double, int>> candidates(nj);
  for (int v = 0; v < nv; ++v) {
    Eigen::Vector3d x = V.row(v).transpose();
    Eigen::Vector3d start = x - 5e-4 * normals.row(v).transpose();
    for (int j = 0; j < nj; ++j) {
      Eigen::Vector3d a = skeleton.positions.row(j).transpose(), b = skeleton.boneEnds.row(j).transpose();
      candidates[j] = {(closestOnSegment(x, a, b) - x).norm(), j};
    }
    std::sort(candidates.begin(), candidates.end());
    double best = -1;
    for (const auto& [distance, j] : candidates) {
      if (best > 0 && distance > best * 1.0001 + 1e-9) break;
      Eigen::Vector3d target =
          closestOnSegment(x, skeleton.positions.row(j).transpose(), skeleton.boneEnds.row(j).transpose());
      if (surface.intersects(start, target)) continue;
      if (best < 0) best = distance;
      nearest(v, j) = 1.0;
    }
    if (best > 0) {
      nearest.row(v) /= nearest.row(v).sum();
      heat[v] = options.heatScale / std::max(best * best, 1e-8);
    }
  }

  // (-L + M H) w_j = M H p_j for every joint; one factorisation.
  Eigen::VectorXd mh = mass.cwiseProduct(heat);
  Eigen::SparseMatrix<double> system = -laplacian;
  for (int v = 0; v < nv; ++v) system.coeffRef(v, v) += mh[v];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system);
  PIXELCLOTH_CHECK(solver.info() == Eigen::Success,
                   "skin weights: the bone-heat system cannot be factored (is every part of the mesh near a bone?)");
  Eigen::MatrixXd rhs = mh.asDiagonal() * nearest;
  Eigen::MatrixXd weights = solver.solve(rhs);

  for (int v = 0; v < nv; ++v) {
    for (int j = 0; j < nj; ++j)
      if (!(weights(v, j) >= options.minimumWeight)) weights(v, j) = 0;
    double sum = weights.row(v).sum();
    if (sum <= 0) {
      weights.row(v) = nearest.row(v);  // unreachable by heat: fall back to its nearest bone
      if (weights.row(v).sum() <= 0) weights(v, candidates.front().second) = 1;
      sum = weights.row(v).sum();
    }
    weights.row(v) /= sum;
  }
  return weights;
}

Eigen::MatrixXd corruptUpperArmWeights(const Skeleton& skeleton, const Eigen::MatrixXd& weights,
                                       const std::string& mode, double fraction) {
  PIXELCLOTH_CHECK(mode == "torso" || mode == "torso+arm",
                   "corrupt weights: mode must be 'torso' or 'torso+arm', got '" << mode << "'");
  PIXELCLOTH_CHECK(fraction >= 0 && fraction <= 1, "corrupt weights: fraction must be in [0, 1], got " << fraction);
  PIXELCLOTH_CHECK(weights.cols() == skeleton.numJoints(), "corrupt weights: " << weights.cols()
                                                                               << " weight columns for "
                                                                               << skeleton.numJoints() << " joints");
  Eigen::MatrixXd out = weights;
  int torso = skeleton.index("spine1");
  for (const auto& [arm, other] : {std::pair{"l_arm", "r_arm"}, std::pair{"r_arm", "l_arm"}}) {
    int a = skeleton.index(arm), o = skeleton.index(other);
    for (int v = 0; v < out.rows(); ++v) {
      double moved = fraction * weights(v, a);
      if (moved == 0) continue;
      out(v, a) -= moved;
      if (mode == "torso") {
        out(v, torso) += moved;
      } else {
        out(v, torso) += 0.5 * moved;
        out(v, o) += 0.5 * moved;
      }
    }
  }
  return out;
}

std::vector<BodyPart> collisionParts(const Body& body, double overlap) {
  const Skeleton& s = body.skeleton;
  const Eigen::MatrixXd& w = body.weights;
  Eigen::VectorXd left = w.col(s.index("l_arm")) + w.col(s.index("l_forearm"));
  Eigen::VectorXd right = w.col(s.index("r_arm")) + w.col(s.index("r_forearm"));
  std::vector<BodyPart> parts = {{"left_arm", {}, {}}, {"right_arm", {}, {}}, {"torso", {}, {}}};
  const Eigen::MatrixX3i& F = body.mesh.F;
  for (int f = 0; f < F.rows(); ++f) {
    bool inLeft = false, inRight = false, inTorso = false;
    for (int k = 0; k < 3; ++k) {
      int v = F(f, k);
      inLeft |= left[v] > overlap;
      inRight |= right[v] > overlap;
      inTorso |= left[v] + right[v] < 1.0 - overlap;
    }
    if (inLeft) parts[0].faces.push_back(f);
    if (inRight) parts[1].faces.push_back(f);
    if (inTorso) parts[2].faces.push_back(f);
  }
  for (BodyPart& part : parts) {
    for (int f : part.faces)
      for (int k = 0; k < 3; ++k) part.vertices.push_back(F(f, k));
    std::sort(part.vertices.begin(), part.vertices.end());
    part.vertices.erase(std::unique(part.vertices.begin(), part.vertices.end()), part.vertices.end());
  }
  return parts;
}

Eigen::MatrixX3d Body::posedVertices(const Pose& pose) const { return skin(skeleton, mesh.V, weights, pose); }

Mesh Body::posedMesh(const Pose& pose) const {
  Mesh posed;
  posed.V = posedVertices(pose);
  posed.F = mesh.F;
  return posed;
}

JointPositions posedJoints(const Body& body, const Pose& pose) {
  JointTransforms transforms = forwardKinematics(body.skeleton, pose);
  JointPositions joints;
  for (const auto& name : kPoseJoints) joints[name] = transforms.positions.row(body.skeleton.index(name)).transpose();
  return joints;
}

void Body::validate(const std::string& context) const {
  mesh.validate(context);
  skeleton.validate(context);
  PIXELCLOTH_CHECK(weights.rows() == mesh.numVertices() && weights.cols() == skeleton.numJoints(),
                   context << ": skin weights are " << weights.rows() << " x " << weights.cols() << ", expected "
                           << mesh.numVertices() << " vertices x " << skeleton.numJoints() << " joints");
  for (int v = 0; v < weights.rows(); ++v) {
    PIXELCLOTH_CHECK(weights.row(v).allFinite() && weights.row(v).minCoeff() >= 0,
                     context << ": skin weights of vertex " << v + 1 << " are negative or not finite");
    PIXELCLOTH_CHECK(std::abs(weights.row(v).sum() - 1.0) < 1e-3, context << ": skin weights of vertex " << v + 1
                                                                          << " sum to " << weights.row(v).sum()
                                                                          << ", expected 1");
  }
  TopologyReport topology = checkTopology(mesh.numVertices(), mesh.F);
  PIXELCLOTH_CHECK(topology.closedManifold(),
                   context << ": the body mesh must be closed and manifold: " << topology.firstProblem);
  for (const BodyPart& part : parts) {
    for (int f : part.faces)
      PIXELCLOTH_CHECK(f >= 0 && f < mesh.numFaces(), context << ": part '" << part.name << "' uses face " << f
                                                              << ", but the mesh has " << mesh.numFaces());
  }
}

std::vector<std::vector<int>> meetingParts(const std::vector<BodyPart>& parts) {
  std::vector<std::vector<int>> meets(parts.size());
  for (size_t p = 0; p < parts.size(); ++p)
    for (size_t q = 0; q < parts.size(); ++q) {
      if (q == p) continue;
      const std::vector<int>&a = parts[p].vertices, &b = parts[q].vertices;
      // Both sorted: walk them together until a shared vertex.
      for (size_t i = 0, j = 0; i < a.size() && j < b.size();) {
        if (a[i] == b[j]) {
          meets[p].push_back(static_cast<int>(q));
          break;
        }
        a[i] < b[j] ? ++i : ++j;
      }
    }
  return meets;
}

}  // namespace pixelcloth::body
