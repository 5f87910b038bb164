#include "pixelcloth/viz/previews.h"

#include <algorithm>

#include "pixelcloth/viz/draw.h"

namespace pixelcloth::viz {

using namespace core;
using namespace body;
using namespace garment;

namespace {
constexpr double kSkin[3] = {0.87, 0.78, 0.70};

Eigen::Vector3d toUnit(Color c) { return Eigen::Vector3d(c[0], c[1], c[2]) / 255.0; }

Eigen::AlignedBox3d boundsOf(const Eigen::MatrixX3d& V) {
  Eigen::AlignedBox3d box;
  for (int i = 0; i < V.rows(); ++i) box.extend(V.row(i).transpose().eval());
  return box;
}

void drawSkeleton(RgbImage& image, const Projection& projection, const Skeleton& skeleton,
                  const Eigen::MatrixX3d& positions) {
  for (int j = 0; j < skeleton.numJoints(); ++j) {
    int p = skeleton.parents[j];
    if (p >= 0)
      drawLine(image, projection.toPixel(positions.row(p).transpose()),
               projection.toPixel(positions.row(j).transpose()), {40, 40, 40}, 2.0);
  }
  for (int j = 0; j < skeleton.numJoints(); ++j) {
    Eigen::Vector2d q = projection.toPixel(positions.row(j).transpose());
    drawDisc(image, q, 4.0, {30, 30, 30});
    drawDisc(image, q, 2.5, paletteColor(j));
  }
}
}  // namespace

Eigen::Vector3d jointColor(int joint) { return toUnit(paletteColor(joint)); }

RgbImage contactSheet(const std::vector<RgbImage>& pictures, int columns, int gap) {
  if (pictures.empty()) return RgbImage(1, 1);
  columns = std::max(1, std::min(columns, static_cast<int>(pictures.size())));
  int rows = (static_cast<int>(pictures.size()) + columns - 1) / columns;
  int cellW = 0, cellH = 0;
  for (const RgbImage& p : pictures) {
    cellW = std::max(cellW, p.width);
    cellH = std::max(cellH, p.height);
  }
  RgbImage sheet(columns * cellW + (columns + 1) * gap, rows * cellH + (rows + 1) * gap);
  for (size_t i = 0; i < pictures.size(); ++i) {
    int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
    paste(sheet, pictures[i], gap + c * (cellW + gap), gap + r * (cellH + gap));
  }
  return sheet;
}

RgbImage renderBodySheet(const Body& body, int panelSize) {
  View front;
  front.width = front.height = panelSize;
  RenderMesh skin{body.mesh.V, body.mesh.F, {}, {}, {kSkin[0], kSkin[1], kSkin[2]}};
  Projection projection;
  RgbImage shaded = renderMeshes({skin}, front, &projection);
  drawSkeleton(shaded, projection, body.skeleton, body.skeleton.positions);

  RenderMesh weights = skin;
  weights.vertexColors = Eigen::MatrixX3d::Zero(body.mesh.numVertices(), 3);
  for (int v = 0; v < body.mesh.numVertices(); ++v)
    for (int j = 0; j < body.skeleton.numJoints(); ++j)
      weights.vertexColors.row(v) += body.weights(v, j) * jointColor(j).transpose();
  RgbImage weightPicture = renderMeshes({weights}, front);

  RenderMesh parts = skin;
  parts.faceColors = Eigen::MatrixX3d::Zero(body.mesh.numFaces(), 3);
  Eigen::VectorXi count = Eigen::VectorXi::Zero(body.mesh.numFaces());
  const Eigen::Vector3d partColors[3] = {{0.85, 0.25, 0.2}, {0.2, 0.4, 0.85}, {0.75, 0.75, 0.72}};
  for (size_t p = 0; p < body.parts.size() && p < 3; ++p) {
    for (int f : body.parts[p].faces) {
      parts.faceColors.row(f) += partColors[p].transpose();
      ++count[f];
    }
  }
  for (int f = 0; f < body.mesh.numFaces(); ++f) {
    if (count[f] > 1)
      parts.faceColors.row(f) << 0.65, 0.35, 0.75;  // overlap of an arm and the torso
    else if (count[f] == 0)
      parts.faceColors.row(f) << 0.2, 0.2, 0.2;
  }
  RgbImage partPicture = renderMeshes({parts}, front);

  View side = front;
  side.azimuthDegrees = 90;
  side.bounds = boundsOf(body.mesh.V);
  RgbImage sidePicture = renderMeshes({skin}, side);
  return contactSheet({shaded, weightPicture, partPicture, sidePicture}, 4);
}

RgbImage renderPosedBody(const Body& body, const Pose& pose, const View& view, bool withSkeleton) {
  RenderMesh skin{body.posedVertices(pose), body.mesh.F, {}, {}, {kSkin[0], kSkin[1], kSkin[2]}};
  Projection projection;
  RgbImage picture = renderMeshes({skin}, view, &projection);
  if (withSkeleton) drawSkeleton(picture, projection, body.skeleton, forwardKinematics(body.skeleton, pose).positions);
  return picture;
}

RgbImage renderGarmentOnBody(const Garment& garment, const Body* body, int panelSize,
                             const Eigen::MatrixX3d* vertexColors) {
  RenderMesh cloth{garment.mesh.V, garment.mesh.F, {}, {}, {0.5, 0.5, 0.5}};
  if (vertexColors) {
    cloth.vertexColors = *vertexColors;
  } else {
    cloth.faceColors.resize(garment.mesh.numFaces(), 3);
    for (int f = 0; f < garment.mesh.numFaces(); ++f)
      cloth.faceColors.row(f) = (0.35 + 0.65 * toUnit(paletteColor(garment.facePanel[f])).array()).matrix().transpose();
  }
  std::vector<RenderMesh> meshes = {cloth};
  if (body) meshes.push_back(RenderMesh{body->mesh.V, body->mesh.F, {}, {}, {kSkin[0], kSkin[1], kSkin[2]}});
  View front;
  front.width = front.height = panelSize;
  front.bounds = boundsOf(body ? body->mesh.V : garment.mesh.V);
  View back = front;
  back.azimuthDegrees = 180;
  View threeQuarter = front;
  threeQuarter.azimuthDegrees = 35;
  threeQuarter.elevationDegrees = 15;
  return contactSheet({renderMeshes(meshes, front), renderMeshes(meshes, threeQuarter), renderMeshes(meshes, back)}, 3);
}

}  // namespace pixelcloth::viz
