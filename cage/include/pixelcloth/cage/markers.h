#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/cage/cage.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::cage {

/// One marker: a garment vertex on the cage whose 3D position is known (captured, or taken from a dataset sample).
/// A marker is either a cage junction (`node` set) or a point along one curve (`curve` set), never both.
struct Marker {
  std::string name;   ///< unique in its set, e.g. "neck_side_left" style node names or "chest:3"
  int vertex = -1;    ///< garment vertex (row of Garment::mesh.V)
  std::string curve;  ///< the curve it lies on, for a point along a curve; "" for a junction
  std::string node;   ///< the cage node it sits at, for a junction; "" for a point along a curve
  /// World position, metres; NaN (the default) when the set only defines where the markers are.
  Eigen::Vector3d position = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  bool hasPosition() const { return position.allFinite(); }
};

/// A marker set for one garment template (docs/markers.md):
///   {"garment": "tshirt", "markers": [{"name", "vertex", "curve" | "node", "position": [x, y, z]}, ...]}.
struct MarkerSet {
  std::string garment;  ///< Garment::name of the template it is defined on
  std::vector<Marker> markers;

  /// Throws InputError (prefixed with `context`, e.g. the file name) when the garment name differs from
  /// `garment.name`, a vertex is out of range, a curve or node is unknown to `cage`, a curve marker's vertex is not on
  /// its curve or a node marker's vertex is not its node's, names repeat, a marker names both or neither of curve and
  /// node, a position is not finite, or (when `requirePositions`) a position is missing.
  void validate(const garment::Garment& garment, const Cage& cage, const std::string& context,
                bool requirePositions) const;
};

/// Where markers go (DESIGN.md, "Key-point-to-cage spline solver").
struct MarkerOptions {
  /// Target spacing of the markers along each curve, metres of rest arc length: between two consecutive junctions on
  /// a curve that are d apart, round(d / spacing) - 1 evenly spaced markers (at least none), snapped to curve
  /// vertices. In [0.01, 10].
  double spacing = 0.10;
  void validate() const;
};

/// Defines the markers of a garment's cage: every node of `cage`, then points along each curve at about
/// `options.spacing` apart in rest arc length (pattern-space lengths, `patternArcLengths` in geodesic.h) between the
/// nodes that lie on that curve (a closed curve without nodes starts at its first vertex), and always at least three
/// markers on a closed curve (what its spline needs). Positions are NaN.
MarkerSet defineMarkers(const garment::Garment& garment, const Cage& cage, const MarkerOptions& options = {});

/// How marker positions are taken from ground truth to mimic capture.
struct CaptureOptions {
  double noise = 0;        ///< standard deviation of Gaussian noise per coordinate, metres (>= 0)
  double dropout = 0;      ///< fraction in [0, 1) of the curve markers left out (junction markers are always kept)
  std::uint64_t seed = 0;  ///< seeds noise and dropout (mt19937_64)
  void validate() const;
};

/// The markers of `definition` with positions read from `positions` (#V x 3, metres, e.g. a dataset sample), then
/// noise added and curve markers dropped as `options` say. Throws InputError when a vertex is out of range.
MarkerSet placeMarkers(const MarkerSet& definition, const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                       const CaptureOptions& options = {});

/// JSON form (docs/markers.md); positions written only when known.
nlohmann::json toJson(const MarkerSet& markers);
/// Parses the JSON form; throws InputError naming `context` and the marker for missing or mistyped fields and
/// non-finite positions. Semantic checks against a garment are `MarkerSet::validate`.
MarkerSet markersFromJson(const nlohmann::json& json, const std::string& context);
/// Reads a marker file (InputError naming the file when missing or malformed).
MarkerSet readMarkers(const std::filesystem::path& path);
/// Writes a marker file atomically.
void writeMarkers(const std::filesystem::path& path, const MarkerSet& markers);

}  // namespace pixelcloth::cage
