#include <Eigen/Geometry>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

using namespace cage;

namespace {
core::Color kindColor(CurveKind kind) {
  switch (kind) {
    case CurveKind::Loop:
      return {214, 39, 40};
    case CurveKind::CentreLine:
      return {31, 90, 200};
    case CurveKind::Seam:
      return {30, 150, 50};
    case CurveKind::Opening:
      return {20, 20, 20};
    case CurveKind::Split:
      return {255, 127, 14};
  }
  return {0, 0, 0};
}
}  // namespace

core::RgbImage renderCageOnMesh(const core::Mesh& mesh, const Cage& cage, int panelSize) {
  Eigen::MatrixX3d normals = core::vertexNormals(mesh.V, mesh.F);
  std::vector<core::RgbImage> pictures;
  for (double azimuth : {0.0, 180.0, 40.0}) {
    viz::View view;
    view.width = view.height = panelSize;
    view.azimuthDegrees = azimuth;
    view.elevationDegrees = azimuth == 40.0 ? 15.0 : 0.0;
    viz::Projection projection;
    core::RgbImage picture =
        viz::renderMeshes({viz::RenderMesh{mesh.V, mesh.F, {}, {}, {0.87, 0.80, 0.74}}}, view, &projection);
    // A vertex faces the camera when its normal has a positive component towards the viewer.
    auto facing = [&](int v) { return (projection.rotation * normals.row(v).transpose()).z() > 0.05; };
    for (const CageCurve& c : cage.curves) {
      const size_t n = c.vertices.size();
      for (size_t i = 0; i + 1 < n || (c.closed && i < n); ++i) {
        int a = c.vertices[i], b = c.vertices[(i + 1) % n];
        if (!facing(a) || !facing(b)) continue;
        viz::drawLine(picture, projection.toPixel(mesh.V.row(a).transpose()),
                      projection.toPixel(mesh.V.row(b).transpose()), kindColor(c.kind), 2.5);
      }
    }
    for (const CageNode& node : cage.nodes) {
      if (!facing(node.vertex)) continue;
      Eigen::Vector2d p = projection.toPixel(mesh.V.row(node.vertex).transpose());
      viz::drawDisc(picture, p, 4.0, {20, 20, 20});
      viz::drawDisc(picture, p, 2.5, {255, 230, 80});
    }
    pictures.push_back(picture);
  }
  return viz::contactSheet(pictures, 3);
}

}  // namespace pixelcloth::viz
