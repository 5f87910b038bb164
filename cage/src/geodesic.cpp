// Rest lengths of cage curves: pattern-space and 3D polyline arc lengths (geodesic ones through
// core::GeodesicDistance).
#include "pixelcloth/cage/geodesic.h"

#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::cage {

namespace {
const core::EnumNames<RestLengths, 3> kRestLengths{
    "rest lengths",
    {{{RestLengths::Pattern, "pattern"}, {RestLengths::Polyline, "polyline"}, {RestLengths::Geodesic, "geodesic"}}}};
}  // namespace

const char* restLengthsName(RestLengths lengths) { return kRestLengths.name(lengths); }

RestLengths restLengthsFromName(const std::string& name, const std::string& context) {
  return kRestLengths.fromName(name, context);
}

double patternEdgeLength(const garment::Garment& garment, int a, int b) {
  const int n = garment.mesh.numVertices();
  PIXELCLOTH_CHECK(a >= 0 && b >= 0 && a < n && b < n,
                   garment.name << ": edge (" << a << ", " << b << ") out of range for " << n << " vertices");
  for (int l = 0; l < garment.numLayouts(); ++l) {
    const int ua = garment.vertexUV(a, l), ub = garment.vertexUV(b, l);
    if (ua >= 0 && ub >= 0) return (garment.mesh.UV.row(ua) - garment.mesh.UV.row(ub)).norm();
  }
  PIXELCLOTH_FAIL(garment.name << ": vertices " << a << " and " << b << " share no layout, so the edge has no "
                               << "pattern-space length");
}

std::vector<double> patternArcLengths(const garment::Garment& garment, const CageCurve& curve) {
  const size_t n = curve.vertices.size();
  std::vector<double> s(1, 0.0);
  for (size_t i = 1; i < n + (curve.closed ? 1 : 0); ++i)
    s.push_back(s.back() + patternEdgeLength(garment, curve.vertices[i - 1], curve.vertices[i % n]));
  return s;
}

std::vector<double> polylineArcLengths(const Eigen::Ref<const Eigen::MatrixX3d>& V, const CageCurve& curve) {
  const size_t n = curve.vertices.size();
  std::vector<double> s(1, 0.0);
  for (size_t i = 1; i < n + (curve.closed ? 1 : 0); ++i) {
    const int a = curve.vertices[i - 1], b = curve.vertices[i % n];
    PIXELCLOTH_CHECK(a >= 0 && b >= 0 && a < V.rows() && b < V.rows(),
                     "curve '" << curve.name << "': vertex out of range for " << V.rows() << " positions");
    s.push_back(s.back() + (V.row(a) - V.row(b)).norm());
  }
  return s;
}

}  // namespace pixelcloth::cage
