#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace pixelcloth::core {

/// A triangle mesh as Eigen matrices (libigl style), with optional per-corner texture coordinates
/// and named per-vertex / per-face attributes.
/// The largest coordinate a mesh may hold, in any unit: beyond it squared lengths and cross products overflow.
constexpr double kMaxCoordinate = 1e9;

struct Mesh {
  Eigen::MatrixX3d V;    ///< #V x 3 vertex positions, metres
  Eigen::MatrixX3i F;    ///< #F x 3 vertex indices, counter-clockwise seen from outside
  Eigen::MatrixX2d UV;   ///< #UV x 2 texture coordinates (pattern space, metres); empty when absent
  Eigen::MatrixX3i FUV;  ///< #F x 3 indices into UV, one per face corner; empty when absent
  std::map<std::string, Eigen::MatrixXd> vertexAttributes;  ///< each #V x k
  std::map<std::string, Eigen::VectorXi> faceAttributes;    ///< each #F

  int numVertices() const { return static_cast<int>(V.rows()); }
  int numFaces() const { return static_cast<int>(F.rows()); }
  bool hasUV() const { return UV.rows() > 0 && FUV.rows() == F.rows(); }

  /// Throws `InputError` (prefixed with `context`, e.g. a file name) if indices are out of range,
  /// coordinates are not finite, a face repeats a vertex, or attribute sizes do not match.
  void validate(const std::string& context = "mesh") const;
};

/// Barycentric coordinates of `p` (on or near the triangle's plane) in triangle (a, b, c), clamped into the
/// triangle and renormalised; (1, 0, 0) for a degenerate triangle.
Eigen::Vector3d barycentricCoordinates(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

/// Barycentric coordinates of the point of triangle (a, b, c) closest to `p` (exact, by the triangle's Voronoi
/// regions: interior, edges, corners); a degenerate triangle gives its closest corner or edge point.
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

/// Per-face unit normals (#F x 3) and per-vertex area-weighted unit normals (#V x 3).
Eigen::MatrixX3d faceNormals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
Eigen::MatrixX3d vertexNormals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

/// Result of a topology check: counts of problems, and the first problem in words (empty if none).
struct TopologyReport {
  int boundaryEdges = 0;        ///< edges used by exactly one face
  int nonManifoldEdges = 0;     ///< edges used by more than two faces
  int inconsistentEdges = 0;    ///< edges used twice in the same direction (faces not consistently oriented)
  int nonManifoldVertices = 0;  ///< vertices whose faces do not form one fan
  int isolatedVertices = 0;     ///< vertices used by no face
  int components = 0;           ///< connected components of faces
  /// The first problem found, vertices counted from 1 as in an OBJ file ("edge (12, 13) is on a boundary ...").
  std::string firstProblem;
  /// Which component it is on: 1 the largest (most faces), 2 the next...; 0 when there is no problem.
  int firstProblemComponent = 0;
  std::vector<int> componentFaces;  ///< faces of each component, largest first
  bool closedManifold() const {
    return boundaryEdges == 0 && nonManifoldEdges == 0 && inconsistentEdges == 0 && nonManifoldVertices == 0;
  }
};

/// Checks whether (V, F) is a closed, consistently oriented 2-manifold.
TopologyReport checkTopology(int numVertices, const Eigen::MatrixX3i& F);

/// Each face's connected component (faces joined through shared vertices), numbered 0 for the largest (most faces),
/// 1 for the next, and so on.
std::vector<int> faceComponents(int numVertices, const Eigen::MatrixX3i& F);

/// The mesh's largest component alone (most faces): the other components' faces and every vertex no kept face uses
/// are dropped, the vertices renumbered in their old order; attributes and texture coordinates follow.
Mesh largestComponent(const Mesh& mesh);

/// Signed volume enclosed by a closed mesh (positive when faces are oriented outwards), m^3.
double enclosedVolume(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

}  // namespace pixelcloth::core
