// The cage on the built-in mannequin: curves along edges, loops where they belong, junctions named like the shirt's.
#include "pixelcloth/cage/body_cage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "pixelcloth/body/body.h"
#include "support/fixtures.h"

namespace pcg = pixelcloth::cage;
namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pg = pixelcloth::garment;

using pixelcloth::testing::mannequin;

namespace {

double curveLength(const pc::Mesh& mesh, const pcg::CageCurve& c) {
  double length = 0;
  size_t n = c.vertices.size();
  for (size_t i = 0; i + 1 < n || (c.closed && i < n); ++i)
    length += (mesh.V.row(c.vertices[i]) - mesh.V.row(c.vertices[(i + 1) % n])).norm();
  return length;
}
}  // namespace

TEST(BodyCage, CurvesFollowEdgesAndLoopsHaveBodySizedLengths) {
  const pb::Body& body = mannequin();
  pcg::Cage cage = pcg::bodyCage(body);
  EXPECT_NO_THROW(cage.validate(body.mesh.F, body.mesh.numVertices()));
  for (const char* name : {"neckline",
                           "chest",
                           "waist",
                           "hem",
                           "bicep_left",
                           "bicep_right",
                           "sleeve_hem_left",
                           "sleeve_hem_right",
                           "centre_front",
                           "centre_back",
                           "side_left",
                           "side_right",
                           "shoulder_left",
                           "shoulder_right",
                           "sleeve_top_left",
                           "underarm_left",
                           "armhole_front_left",
                           "armhole_back_left",
                           "armhole_front_right",
                           "armhole_back_right"}) {
    EXPECT_NE(cage.findCurve(name), nullptr) << name;
  }
  // A loop around the chest of a ~0.33 x 0.22 m cross-section is 0.8-1.0 m; an upper arm of radius ~5 cm ~0.3 m.
  double chest = curveLength(body.mesh, *cage.findCurve("chest"));
  EXPECT_GT(chest, 0.75);
  EXPECT_LT(chest, 1.05);
  double bicep = curveLength(body.mesh, *cage.findCurve("bicep_left"));
  EXPECT_GT(bicep, 0.25);
  EXPECT_LT(bicep, 0.4);
  // The chest loop stays level: every vertex within 2 cm of the loop's mean height.
  const pcg::CageCurve& loop = *cage.findCurve("chest");
  double mean = 0;
  for (int v : loop.vertices) mean += body.mesh.V(v, 1) / loop.vertices.size();
  for (int v : loop.vertices) EXPECT_NEAR(body.mesh.V(v, 1), mean, 0.02);
  // The left side line runs down the left of the torso.
  for (int v : cage.findCurve("side_left")->vertices) EXPECT_GT(body.mesh.V(v, 0), 0.08);
}

TEST(BodyCage, JunctionsCarryTheNamesOfTheCurvesThatMeet) {
  pcg::Cage cage = pcg::bodyCage(mannequin());
  for (const char* name :
       {"armhole_back_left/armhole_front_left/side_left/underarm_left",
        "armhole_back_left/armhole_front_left/shoulder_left/sleeve_top_left", "neckline/shoulder_left",
        "centre_front/neckline", "centre_front/chest", "chest/side_left", "hem/side_right",
        "bicep_left/sleeve_top_left", "sleeve_hem_left/underarm_left", "centre_back/waist"}) {
    EXPECT_GE(cage.findNode(name), 0) << name;
  }
  // Every node lies on each curve it names.
  for (const pcg::CageNode& node : cage.nodes) {
    std::stringstream names(node.name);
    std::string curve;
    while (std::getline(names, curve, '/')) {
      const pcg::CageCurve* c = cage.findCurve(curve);
      ASSERT_NE(c, nullptr) << node.name;
      EXPECT_NE(std::find(c->vertices.begin(), c->vertices.end(), node.vertex), c->vertices.end()) << node.name;
    }
  }
}

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/garment/garment.h"

TEST(BodyCage, EveryBodyJunctionHasItsNamesakeOnTheShirt) {
  pcg::Cage body = pcg::bodyCage(mannequin());
  pcg::Cage shirt = pcg::garmentCage(pg::makeTShirt());
  ASSERT_GE(body.nodes.size(), 20u);
  for (const pcg::CageNode& node : body.nodes) EXPECT_GE(shirt.findNode(node.name), 0) << node.name;
}

TEST(BodyCage, WorksOnAnImportedBody) {
  // The mannequin lowered into an A-pose, written as a mesh plus joints, imported back (arms rotated to the T-pose).
  const pb::Body& original = mannequin();
  pb::Pose pose = pb::armsLowered(35);
  pc::Mesh mesh = original.posedMesh(pose);
  pb::JointPositions joints = pb::posedJoints(original, pose);
  pb::Body imported = pb::importBody(mesh, joints, "apose.obj");
  pcg::Cage cage = pcg::bodyCage(imported);
  EXPECT_NO_THROW(cage.validate(imported.mesh.F, imported.mesh.numVertices()));
  EXPECT_EQ(cage.nodes.size(), pcg::bodyCage(original).nodes.size());
  double chest = curveLength(imported.mesh, *cage.findCurve("chest"));
  EXPECT_NEAR(chest, curveLength(original.mesh, *pcg::bodyCage(original).findCurve("chest")), 0.05);
}
