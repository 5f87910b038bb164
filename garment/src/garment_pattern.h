#pragma once
// Private to pixelcloth_core: the flat-pattern mesher shared by the garment templates. No CGAL types here; CGAL
// stays inside garment.cpp.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment::pattern {

/// A curve of a flat pattern: a polyline in garment coordinates (x to the wearer's left, y up), metres. Curves meet
/// only at their end points and at their joints, which must be bit-identical where they are shared.
struct Curve {
  std::string name;
  std::vector<Eigen::Vector2d> points;  ///< >= 2 points
  /// Carried by every layout and stitched: all layouts must end up with the same vertices along it.
  bool stitched = false;
  /// Indices of interior points where other curves end or cross this one (cage lines meeting a seam, a hem or
  /// another line). Each becomes a mesh vertex at exactly its coordinates; on a stitched curve, at the same
  /// arc-length parameter in every layout.
  std::vector<int> joints = {};
  double length() const;
  /// Arc-length fraction of points[index]; `at` returns that point exactly for this fraction.
  double paramOf(int index) const;
  /// Point at arc-length fraction t in [0, 1]; the end points and every polyline point are returned exactly.
  Eigen::Vector2d at(double t) const;
};

/// A straight-piece polyline through `points` whose interior points are all joints.
Curve polylineCurve(const std::string& name, const std::vector<Eigen::Vector2d>& points, bool stitched);

/// A straight curve from a to b.
Curve straightCurve(const std::string& name, const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool stitched);

/// One layout: the curves bounding it and those sewn inside it (both are just constraints to the mesher; the
/// meshed domain is everything the constraints enclose). Layout coordinates: u = mirrored ? -x : x, v = y.
struct Layout {
  std::string name;
  bool mirrored = false;
  std::vector<int> curves;  ///< indices into the curve list
};

/// The stitched, merged triangulation of all layouts.
struct MergedPattern {
  Eigen::MatrixX2d XY;         ///< #V x 2 garment coordinates (x, y) of each vertex
  Eigen::MatrixX3i F;          ///< #F x 3, counter-clockwise in its layout's UV
  Eigen::MatrixX2d UV;         ///< layout coordinates, one row per (layout, vertex)
  Eigen::MatrixX3i FUV;        ///< #F x 3 into UV
  Eigen::VectorXi faceLayout;  ///< #F
  Eigen::MatrixXi vertexUV;    ///< #V x #layouts, UV row or -1
  /// chains[layout][curve]: the vertices along the curve from t = 0 to t = 1 (empty if the layout lacks the curve).
  std::vector<std::vector<std::vector<int>>> chains;
  PatternMeshingStats stats;
};

/// Meshes every layout with CGAL's constrained Delaunay mesher (shape bound 0.125, i.e. min angle 20.7 degrees),
/// matches the stitched curves' vertices across layouts, merges, and searches the edge-length bound so that the merged
/// mesh has about `targetVertices` vertices. `area` is the total pattern area (for the first guess). The curves are
/// first sampled every `boundarySpacing` times the mesher's edge-length bound.
MergedPattern meshPattern(const std::vector<Curve>& curves, const std::vector<Layout>& layouts, int targetVertices,
                          double area, double boundarySpacing);

/// Boundary loops of a mesh with boundary, each ordered along its boundary half-edges (cloth on the left). Loops start
/// at their smallest vertex index; the list is sorted by that index.
std::vector<std::vector<int>> boundaryLoops(int numVertices, const Eigen::MatrixX3i& F);

/// Smallest interior angle of any triangle (UV, FUV), degrees.
double minAngleDegrees(const Eigen::MatrixX2d& UV, const Eigen::MatrixX3i& FUV);

}  // namespace pixelcloth::garment::pattern
