// Patch segmentation from cut edges, on the built-in T-shirt.
#include "pixelcloth/patches/patch.h"

#include <gtest/gtest.h>

#include <set>

#include "pixelcloth/garment/garment.h"

namespace pp = pixelcloth::patches;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;

TEST(Segmentation, WithoutCutsEachLayoutIsOnePatch) {
  pg::Garment shirt = pg::makeTShirt();
  std::vector<pp::Patch> patches = pp::segmentPatches(shirt, {});
  ASSERT_EQ(patches.size(), 2u);  // front and back layouts
  size_t faces = 0;
  for (const pp::Patch& p : patches) {
    faces += p.faces.size();
    EXPECT_EQ(p.boundary.size() + p.interior.size(), p.vertices.size());
  }
  EXPECT_EQ(faces, static_cast<size_t>(shirt.mesh.numFaces()));
}

TEST(Segmentation, ArmholeSeamsCutTheSleevesOff) {
  pg::Garment shirt = pg::makeTShirt();
  std::vector<std::pair<int, int>> cuts;
  for (const pg::Seam& seam : shirt.seams)
    if (!seam.joinsLayouts)
      for (size_t i = 0; i + 1 < seam.vertices.size(); ++i) cuts.emplace_back(seam.vertices[i], seam.vertices[i + 1]);
  std::vector<pp::Patch> patches = pp::segmentPatches(shirt, cuts);
  ASSERT_EQ(patches.size(), 6u);  // per layout: torso and two sleeve halves
  for (const pp::Patch& p : patches) {
    pp::PatchMesh mesh = pp::patchMesh(shirt, p);
    // Counter-clockwise boundary in UV: positive signed area.
    double area = 0;
    for (size_t i = 0; i < mesh.boundary.size(); ++i) {
      Eigen::Vector2d a = mesh.uv.row(mesh.boundary[i]), b = mesh.uv.row(mesh.boundary[(i + 1) % mesh.boundary.size()]);
      area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    }
    EXPECT_GT(area, 0.0) << "patch " << p.id;
    EXPECT_EQ(mesh.F.rows(), static_cast<int>(p.faces.size()));
  }
}

#include "pixelcloth/patches/frame.h"

TEST(Frame, LayoutFitsAndBothSidesShareTheScale) {
  pg::Garment shirt = pg::makeTShirt();
  pp::ImageFrame front = pp::layoutFrame(shirt, 0, 512), back = pp::layoutFrame(shirt, 1, 512);
  EXPECT_DOUBLE_EQ(front.metresPerPixel, back.metresPerPixel);
  for (int l = 0; l < 2; ++l) {
    pp::ImageFrame frame = pp::layoutFrame(shirt, l, 512);
    Eigen::AlignedBox2d box = shirt.layoutBounds(l);
    for (Eigen::Vector2d corner : {box.min(), box.max()}) {
      Eigen::Vector2d p = frame.toPixel(corner);
      EXPECT_GE(p.minCoeff(), 0.0);
      EXPECT_LE(p.maxCoeff(), 512.0);
      EXPECT_LT((frame.toPattern(p) - corner).norm(), 1e-12);
    }
  }
  // v up in pattern space is up in the picture: the top of the layout has the smaller row.
  Eigen::AlignedBox2d box = shirt.layoutBounds(0);
  EXPECT_LT(front.toPixel(box.max()).y(), front.toPixel(box.min()).y());
}
