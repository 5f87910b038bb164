// Bone-heat skin weights, weight corruption, collision parts and the inside test, all on closed meshes.
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <memory>

#include "pixelcloth/core/body.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPoint = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<CgalPoint>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

SurfaceMesh toSurfaceMesh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  SurfaceMesh mesh;
  std::vector<SurfaceMesh::Vertex_index> vertices;
  vertices.reserve(V.rows());
  for (int i = 0; i < V.rows(); ++i) vertices.push_back(mesh.add_vertex(CgalPoint(V(i, 0), V(i, 1), V(i, 2))));
  for (int f = 0; f < F.rows(); ++f) {
    auto face = mesh.add_face(vertices[F(f, 0)], vertices[F(f, 1)], vertices[F(f, 2)]);
    PIXELCLOTH_CHECK(face != SurfaceMesh::null_face(), "face " << f << " cannot be added: the mesh is not manifold");
  }
  return mesh;
}

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

std::vector<bool> insideClosedMesh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& P) {
  SurfaceMesh mesh = toSurfaceMesh(V, F);
  CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel> side(mesh);
  std::vector<bool> inside(P.rows());
  for (int i = 0; i < P.rows(); ++i) {
    inside[i] = side(CgalPoint(P(i, 0), P(i, 1), P(i, 2))) == CGAL::ON_BOUNDED_SIDE;
  }
  return inside;
}

Eigen::MatrixXd boneHeatWeights(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Skeleton& skeleton,
                                const SkinWeightOptions& options) {
  options.validate();
  const int nv = static_cast<int>(V.rows());
  const int nj = skeleton.numJoints();

  // Cotangent Laplacian L (negative semi-definite) and lumped (barycentric) mass M.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(F.rows() * 12);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(nv);
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d p[3] = {V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2))};
    double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    for (int k = 0; k < 3; ++k) {
      mass[F(f, k)] += area / 3.0;
      int i = F(f, (k + 1) % 3), j = F(f, (k + 2) % 3);
      Eigen::Vector3d e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
      double cot = e1.dot(e2) / std::max(e1.cross(e2).norm(), 1e-20);
      double w = 0.5 * cot;
      triplets.emplace_back(i, j, w);
      triplets.emplace_back(j, i, w);
      triplets.emplace_back(i, i, -w);
      triplets.emplace_back(j, j, -w);
    }
  }
  Eigen::SparseMatrix<double> laplacian(nv, nv);
  laplacian.setFromTriplets(triplets.begin(), triplets.end());

  // Nearest visible bone per vertex: a bone is visible when the segment from just inside the surface
  // to the bone's closest point does not cross the surface.
  SurfaceMesh surface = toSurfaceMesh(V, F);
  AabbTree tree(faces(surface).first, faces(surface).second, surface);
  tree.accelerate_distance_queries();
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
      Kernel::Segment_3 segment(CgalPoint(start.x(), start.y(), start.z()),
                                CgalPoint(target.x(), target.y(), target.z()));
      if (tree.do_intersect(segment)) continue;
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
                     context << ": skin weights of vertex " << v << " are negative or not finite");
    PIXELCLOTH_CHECK(std::abs(weights.row(v).sum() - 1.0) < 1e-3, context << ": skin weights of vertex " << v
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

}  // namespace pixelcloth::core
