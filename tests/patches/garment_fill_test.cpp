// Filling every patch of the T-shirt from its cage.
#include "pixelcloth/patches/garment_fill.h"

#include <gtest/gtest.h>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"
#include "support/fixtures.h"

namespace pp = pixelcloth::patches;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }
pp::GarmentFill shirtFill() {
  pixelcloth::cage::Cage cage = pixelcloth::cage::garmentCage(shirt());
  return pp::GarmentFill(shirt(), pp::segmentPatches(shirt(), pixelcloth::cage::cutEdges(cage)));
}
}  // namespace

TEST(GarmentFill, KeepsTheCageAndReproducesFieldsLinearInEachLayout) {
  pp::GarmentFill fill = shirtFill();
  ASSERT_EQ(fill.patches().size(), 28u);
  // A field linear in the front layout's UVs on front vertices; every patch sees only its own layout's UVs, and a
  // harmonic fill reproduces linear boundary data exactly. Back-only vertices get another linear field.
  const pg::Garment& g = shirt();
  Eigen::MatrixX3d values(g.mesh.numVertices(), 3);
  for (int v = 0; v < g.mesh.numVertices(); ++v) {
    int layout = g.vertexUV(v, 0) >= 0 ? 0 : 1;
    Eigen::Vector2d uv = g.mesh.UV.row(g.vertexUV(v, layout));
    values.row(v) << 0.3 * uv.x() - 0.1 * uv.y(), 0.02, layout == 0 ? uv.y() : -uv.x();
  }
  Eigen::MatrixX3d filled = fill.fill(values);
  double worst = 0;
  for (const pp::Patch& p : fill.patches()) {
    if (p.layout != 0) continue;
    for (int v : p.interior) worst = std::max(worst, (filled.row(v) - values.row(v)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
  for (const pp::Patch& p : fill.patches())
    for (int v : p.boundary) EXPECT_EQ(filled.row(v), values.row(v));
}

TEST(GarmentFill, InteriorsDependOnlyOnTheCage) {
  pp::GarmentFill fill = shirtFill();
  Eigen::MatrixX3d values = Eigen::MatrixX3d::Random(shirt().mesh.numVertices(), 3);
  Eigen::MatrixX3d scrambled = values;
  for (const pp::Patch& p : fill.patches())
    for (int v : p.interior) scrambled.row(v).setConstant(1e3);
  EXPECT_LT((fill.fill(values) - fill.fill(scrambled)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(fill.fill(values.topRows(10)), pc::InputError);
}
