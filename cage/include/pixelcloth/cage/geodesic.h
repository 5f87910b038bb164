#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "pixelcloth/cage/cage.h"
#include "pixelcloth/core/geodesic.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::cage {

/// Rest lengths of the cage curves, what the length-preserving spline must reproduce (DESIGN.md, "Key-point-to-cage
/// spline solver").
///  - Pattern: lengths of the curve's mesh edges in pattern (UV) space: the cloth's true rest state, as the simulator
///    uses it (default).
///  - Polyline: lengths of the curve's mesh edges on a 3D rest garment (e.g. the dressed shirt).
///  - Geodesic: between two markers, the shortest path over the 3D rest garment's surface (CGAL's
///    Surface_mesh_shortest_path), not restricted to the curve; a reference for the polyline and an option.
enum class RestLengths { Pattern, Polyline, Geodesic };

/// "pattern", "polyline", "geodesic".
const char* restLengthsName(RestLengths lengths);
/// Inverse of restLengthsName; throws InputError listing the names.
RestLengths restLengthsFromName(const std::string& name, const std::string& context);

/// Length in pattern space of the mesh edge (a, b): the UV distance in the first layout that holds both vertices.
/// Seams stitched across layouts have the same length in both. Throws InputError when no layout holds both.
double patternEdgeLength(const garment::Garment& garment, int a, int b);

/// Cumulative rest arc length at each vertex of `curve`, metres: n entries for an open curve (first 0), n + 1 for a
/// closed one (the last is the whole loop, back at the first vertex). From pattern-space edge lengths.
std::vector<double> patternArcLengths(const garment::Garment& garment, const CageCurve& curve);
/// The same from the 3D polyline through `V` (#V x 3).
std::vector<double> polylineArcLengths(const Eigen::Ref<const Eigen::MatrixX3d>& V, const CageCurve& curve);

}  // namespace pixelcloth::cage
