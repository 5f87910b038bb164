// The cage structure: validation and JSON round trip.
#include "pixelcloth/cage/cage.h"

#include <gtest/gtest.h>

#include "pixelcloth/core/error.h"

namespace pcg = pixelcloth::cage;

namespace {
/// A 3 x 3 grid of vertices (2 x 2 quads, 8 triangles).
Eigen::MatrixX3i gridFaces() {
  Eigen::MatrixX3i F(8, 3);
  int f = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      int a = 3 * i + j;
      F.row(f++) << a, a + 1, a + 4;
      F.row(f++) << a, a + 4, a + 3;
    }
  return F;
}
}  // namespace

TEST(Cage, JunctionsAndValidation) {
  pcg::Cage cage;
  cage.curves.push_back({"row", pcg::CurveKind::Split, false, {3, 4, 5}});
  cage.curves.push_back({"column", pcg::CurveKind::CentreLine, false, {1, 4, 7}});
  cage.nodes = pcg::junctions(cage.curves);
  ASSERT_EQ(cage.nodes.size(), 5u);  // four ends and the crossing
  EXPECT_GE(cage.findNode("column/row"), 0);
  EXPECT_NO_THROW(cage.validate(gridFaces(), 9));
  EXPECT_EQ(cage.edges().size(), 4u);

  pcg::Cage jumping = cage;
  jumping.curves[0].vertices = {3, 5};  // no edge between 3 and 5
  EXPECT_THROW(jumping.validate(gridFaces(), 9), pixelcloth::core::InputError);
  pcg::Cage outOfRange = cage;
  outOfRange.curves[1].vertices.push_back(42);
  EXPECT_THROW(outOfRange.validate(gridFaces(), 9), pixelcloth::core::InputError);
}

TEST(Cage, JsonRoundTrip) {
  pcg::Cage cage;
  cage.curves.push_back({"loop", pcg::CurveKind::Loop, true, {0, 1, 4, 3}});
  cage.nodes.push_back({"corner", 0});
  pcg::Cage back = pcg::cageFromJson(pcg::toJson(cage), "cage.json");
  ASSERT_EQ(back.curves.size(), 1u);
  EXPECT_EQ(back.curves[0].vertices, cage.curves[0].vertices);
  EXPECT_TRUE(back.curves[0].closed);
  EXPECT_EQ(back.curves[0].kind, pcg::CurveKind::Loop);
  EXPECT_EQ(back.nodes[0].name, "corner");
  nlohmann::json bad = pcg::toJson(cage);
  bad["curves"][0]["kind"] = "zigzag";
  EXPECT_THROW(pcg::cageFromJson(bad, "cage.json"), pixelcloth::core::InputError);
}
