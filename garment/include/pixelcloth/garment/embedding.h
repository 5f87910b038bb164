#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "pixelcloth/core/mesh.h"

namespace pixelcloth::garment {

/// Where each cloth pixel (garment vertex) sits on the body (DESIGN.md "Offsets"): a body triangle, barycentric
/// coordinates in it, and the pattern's u-direction expressed in that triangle's edges, so the direction follows the
/// triangle when the body is posed.
struct Embedding {
  Eigen::VectorXi triangle;        ///< #C body face per cloth vertex
  Eigen::MatrixX3d barycentric;    ///< #C x 3, non-negative, rows sum to 1
  Eigen::MatrixX2d tangentCoords;  ///< #C x 2: u-direction = a (p1 - p0) + b (p2 - p0) in the rest triangle

  int size() const { return static_cast<int>(triangle.size()); }
  /// Throws InputError (prefixed with `context`) when sizes disagree, a triangle is out of range for `numBodyFaces`,
  /// or barycentric coordinates are negative, not finite or do not sum to 1.
  void validate(int numBodyFaces, const std::string& context = "embedding") const;
};

/// Local frames at the embedded points of a (posed) body: n the body normal (barycentric blend of vertex normals),
/// t the carried u-direction made orthogonal to n, b = n x t. Each #C x 3.
struct EmbeddedFrames {
  Eigen::MatrixX3d origin, t, b, n;
};

/// Embeds `points` (#C x 3, metres) at their closest points on the closed or open body mesh (CGAL AABB tree), with
/// `uDirections` (#C x 3, any length, not parallel to the surface normal) as the pattern's u-direction at each point.
Embedding embedClosest(const Eigen::MatrixX3d& bodyV, const Eigen::MatrixX3i& bodyF, const Eigen::MatrixX3d& points,
                       const Eigen::MatrixX3d& uDirections);

/// The frames of `embedding` on the body with vertices `bodyV` (rest or posed; same faces as when embedded).
EmbeddedFrames embeddedFrames(const Eigen::MatrixX3d& bodyV, const Eigen::MatrixX3i& bodyF, const Embedding& embedding);

/// Offsets (du, dv, dn) of world positions in the frames: du = (x - o).t, dv = (x - o).b, dn = (x - o).n. #C x 3.
Eigen::MatrixX3d offsetsFromPositions(const EmbeddedFrames& frames, const Eigen::MatrixX3d& positions);
/// World positions o + du t + dv b + dn n. #C x 3. Exact inverse of offsetsFromPositions (orthonormal frames).
Eigen::MatrixX3d positionsFromOffsets(const EmbeddedFrames& frames, const Eigen::MatrixX3d& offsets);

/// Writes an embedding into `folder` as three arrays, each atomically: embedding_triangle.npy (#C int32),
/// embedding_barycentric.npy (#C x 3 float64) and embedding_tangent.npy (#C x 2 float64). Validates sizes first.
void saveEmbedding(const std::filesystem::path& folder, const Embedding& embedding);

/// Reads the arrays written by saveEmbedding and checks them (shapes agree, barycentric coordinates valid; triangles
/// below `numBodyFaces` when it is not negative). Throws `InputError` naming the file that is wrong.
Embedding loadEmbedding(const std::filesystem::path& folder, int numBodyFaces = -1);

}  // namespace pixelcloth::garment
