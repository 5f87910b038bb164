// Embedding cloth pixels in the body and the local frames of their offsets (DESIGN.md "Offsets").
#include "pixelcloth/garment/embedding.h"

#include <Eigen/Geometry>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh_index.h"

namespace pixelcloth::garment {

using namespace core;

void Embedding::validate(int numBodyFaces, const std::string& context) const {
  const int n = size();
  PIXELCLOTH_CHECK(barycentric.rows() == n && tangentCoords.rows() == n,
                   context << ": " << n << " triangles but " << barycentric.rows() << " barycentric rows and "
                           << tangentCoords.rows() << " tangent rows");
  for (int i = 0; i < n; ++i) {
    PIXELCLOTH_CHECK(triangle[i] >= 0 && triangle[i] < numBodyFaces,
                     context << ": cloth vertex " << i + 1 << " is embedded in body face " << triangle[i] + 1
                             << ", but the body has " << numBodyFaces << " faces");
    PIXELCLOTH_CHECK(barycentric.row(i).allFinite() && barycentric.row(i).minCoeff() >= -1e-9 &&
                         std::abs(barycentric.row(i).sum() - 1.0) < 1e-6 && tangentCoords.row(i).allFinite(),
                     context << ": cloth vertex " << i + 1 << " has invalid barycentric or tangent coordinates");
  }
}

Embedding embedClosest(const Eigen::MatrixX3d& bodyV, const Eigen::MatrixX3i& bodyF, const Eigen::MatrixX3d& points,
                       const Eigen::MatrixX3d& uDirections) {
  PIXELCLOTH_CHECK(points.rows() == uDirections.rows(),
                   "embedding: " << points.rows() << " points but " << uDirections.rows() << " u-directions");
  const MeshIndex index(bodyV, bodyF);

  Embedding e;
  const int n = static_cast<int>(points.rows());
  e.triangle.resize(n);
  e.barycentric.resize(n, 3);
  e.tangentCoords.resize(n, 2);
  for (int i = 0; i < n; ++i) {
    PIXELCLOTH_CHECK(points.row(i).allFinite() && uDirections.row(i).allFinite(),
                     "embedding: point " << i << " or its u-direction is not finite");
    const MeshHit hit = index.closest(points.row(i).transpose());
    const int f = hit.face;
    Eigen::Vector3d a = bodyV.row(bodyF(f, 0)), b = bodyV.row(bodyF(f, 1)), c = bodyV.row(bodyF(f, 2));
    e.triangle[i] = f;
    e.barycentric.row(i) = hit.barycentric.transpose();
    // The u-direction projected into the triangle's plane, as a combination of its two edges.
    Eigen::Vector3d e1 = b - a, e2 = c - a, normal = e1.cross(e2).normalized();
    Eigen::Vector3d u = uDirections.row(i).transpose();
    u -= u.dot(normal) * normal;
    PIXELCLOTH_CHECK(u.norm() > 1e-6 * uDirections.row(i).norm(),
                     "embedding: the u-direction of point " << i << " is parallel to the body normal");
    Eigen::Matrix<double, 3, 2> edges;
    edges << e1, e2;
    e.tangentCoords.row(i) = edges.colPivHouseholderQr().solve(u.normalized()).transpose();
  }
  return e;
}

EmbeddedFrames embeddedFrames(const Eigen::MatrixX3d& bodyV, const Eigen::MatrixX3i& bodyF, const Embedding& e) {
  e.validate(static_cast<int>(bodyF.rows()));
  Eigen::MatrixX3d normals = vertexNormals(bodyV, bodyF);
  EmbeddedFrames frames;
  const int n = e.size();
  frames.origin.resize(n, 3);
  frames.t.resize(n, 3);
  frames.b.resize(n, 3);
  frames.n.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const int f = e.triangle[i];
    Eigen::Vector3d p[3], normal = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      p[k] = bodyV.row(bodyF(f, k)).transpose();
      normal += e.barycentric(i, k) * normals.row(bodyF(f, k)).transpose();
    }
    frames.origin.row(i) =
        (e.barycentric(i, 0) * p[0] + e.barycentric(i, 1) * p[1] + e.barycentric(i, 2) * p[2]).transpose();
    if (normal.norm() < 1e-12) normal = (p[1] - p[0]).cross(p[2] - p[0]);
    normal.normalize();
    Eigen::Vector3d u = e.tangentCoords(i, 0) * (p[1] - p[0]) + e.tangentCoords(i, 1) * (p[2] - p[0]);
    u -= u.dot(normal) * normal;
    if (u.norm() < 1e-12) u = normal.unitOrthogonal();  // degenerate: any tangent keeps the frame orthonormal
    u.normalize();
    frames.n.row(i) = normal.transpose();
    frames.t.row(i) = u.transpose();
    frames.b.row(i) = normal.cross(u).transpose();
  }
  return frames;
}

Eigen::MatrixX3d offsetsFromPositions(const EmbeddedFrames& frames, const Eigen::MatrixX3d& positions) {
  PIXELCLOTH_CHECK(positions.rows() == frames.origin.rows(),
                   "offsets: " << positions.rows() << " positions for " << frames.origin.rows() << " frames");
  Eigen::MatrixX3d d = positions - frames.origin;
  Eigen::MatrixX3d offsets(d.rows(), 3);
  offsets.col(0) = d.cwiseProduct(frames.t).rowwise().sum();
  offsets.col(1) = d.cwiseProduct(frames.b).rowwise().sum();
  offsets.col(2) = d.cwiseProduct(frames.n).rowwise().sum();
  return offsets;
}

Eigen::MatrixX3d positionsFromOffsets(const EmbeddedFrames& frames, const Eigen::MatrixX3d& offsets) {
  PIXELCLOTH_CHECK(offsets.rows() == frames.origin.rows(),
                   "positions: " << offsets.rows() << " offsets for " << frames.origin.rows() << " frames");
  return frames.origin + frames.t.cwiseProduct(offsets.col(0).replicate(1, 3)) +
         frames.b.cwiseProduct(offsets.col(1).replicate(1, 3)) + frames.n.cwiseProduct(offsets.col(2).replicate(1, 3));
}

}  // namespace pixelcloth::garment
