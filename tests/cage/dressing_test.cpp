// Dressing: cage morph onto the body cage, push-out, edge-length relaxation on the body, embedding.
#include "pixelcloth/cage/dressing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/mesh_index.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace {

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pg = pixelcloth::garment;
namespace pcg = pixelcloth::cage;
using pixelcloth::testing::coarseMannequin;
using pixelcloth::testing::inputErrorOf;
using pixelcloth::testing::tshirt;

/// The T-shirt dressed on the coarse mannequin, once per test process, with the cages it was dressed with.
struct DressedShirt {
  pcg::Cage bodyCage, shirtCage;
  pcg::Dressing dressing;
};

const DressedShirt& dressedShirt() {
  static const DressedShirt dressed = [] {
    DressedShirt d;
    d.bodyCage = pcg::bodyCage(coarseMannequin());
    d.shirtCage = pcg::garmentCage(tshirt());
    d.dressing = pcg::dressGarment(coarseMannequin(), d.bodyCage, tshirt(), d.shirtCage);
    return d;
  }();
  return dressed;
}

/// Distance from p to the polyline through `vertices` of V (closed: last back to first).
double distanceToPolyline(const Eigen::Vector3d& p, const Eigen::MatrixX3d& V, const std::vector<int>& vertices,
                          bool closed) {
  double best = std::numeric_limits<double>::infinity();
  const size_t n = vertices.size();
  for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
    const Eigen::Vector3d a = V.row(vertices[i]), b = V.row(vertices[(i + 1) % n]);
    const double t = std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (p - (a + t * (b - a))).norm());
  }
  return best;
}

/// The q-quantile of log2 of `ratios`.
double log2Quantile(const Eigen::VectorXd& ratios, double q) {
  std::vector<double> logs;
  for (int i = 0; i < ratios.size(); ++i) logs.push_back(std::log2(ratios[i]));
  std::sort(logs.begin(), logs.end());
  return logs[static_cast<size_t>(std::lround(q * (logs.size() - 1)))];
}

TEST(Dressing, CageVerticesWithABodyNamesakeLieOnTheBodyCurve) {
  const DressedShirt& d = dressedShirt();
  const pb::Body& body = coarseMannequin();
  const double clearance = pcg::DressingOptions{}.clearance;
  int checked = 0;
  for (const pcg::CageCurve& curve : d.shirtCage.curves) {
    const pcg::CageCurve* onBody = d.bodyCage.findCurve(curve.name);
    if (onBody == nullptr) continue;
    for (int v : curve.vertices) {
      const double distance =
          distanceToPolyline(d.dressing.relaxed.row(v).transpose(), body.mesh.V, onBody->vertices, onBody->closed);
      EXPECT_LT(distance, clearance + 0.003) << curve.name << " vertex " << v;
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
  EXPECT_EQ(static_cast<int>(d.dressing.cageVertices.size()), [&] {
    std::vector<int> all;
    for (const pcg::CageCurve& curve : d.shirtCage.curves) {
      if (d.bodyCage.findCurve(curve.name)) all.insert(all.end(), curve.vertices.begin(), curve.vertices.end());
    }
    std::sort(all.begin(), all.end());
    return static_cast<int>(std::unique(all.begin(), all.end()) - all.begin());
  }());
  // Side-panel lines have no body namesake: they are free, not part of the morphed cage.
  const pcg::CageCurve* panel = d.shirtCage.findCurve("side_panel_front_left");
  ASSERT_NE(panel, nullptr);
  int onlyOnPanel = 0;
  for (int v : panel->vertices) {
    bool onOtherCurve = false;
    for (const pcg::CageCurve& curve : d.shirtCage.curves) {
      if (&curve != panel && std::count(curve.vertices.begin(), curve.vertices.end(), v)) onOtherCurve = true;
    }
    if (onOtherCurve) continue;
    EXPECT_FALSE(std::binary_search(d.dressing.cageVertices.begin(), d.dressing.cageVertices.end(), v)) << v;
    ++onlyOnPanel;
  }
  EXPECT_GT(onlyOnPanel, 5);
}

TEST(Dressing, JunctionsLandOnTheBodyJunctionOfTheSameName) {
  const DressedShirt& d = dressedShirt();
  const pb::Body& body = coarseMannequin();
  const double clearance = pcg::DressingOptions{}.clearance;
  int matched = 0;
  for (const pcg::CageNode& node : d.shirtCage.nodes) {
    const int onBody = d.bodyCage.findNode(node.name);
    if (onBody < 0) continue;
    const double distance =
        (d.dressing.relaxed.row(node.vertex) - body.mesh.V.row(d.bodyCage.nodes[onBody].vertex)).norm();
    EXPECT_NEAR(distance, clearance, 1e-6) << node.name;
    ++matched;
  }
  EXPECT_GE(matched, static_cast<int>(d.bodyCage.nodes.size()));
}

TEST(Dressing, NoVertexIsInsideTheBodyAfterPushOutOrRelaxation) {
  const DressedShirt& d = dressedShirt();
  const pb::Body& body = coarseMannequin();
  const std::vector<bool> pushedInside = pc::insideClosedMesh(body.mesh.V, body.mesh.F, d.dressing.pushed);
  const std::vector<bool> relaxedInside = pc::insideClosedMesh(body.mesh.V, body.mesh.F, d.dressing.relaxed);
  EXPECT_EQ(std::count(pushedInside.begin(), pushedInside.end(), true), 0);
  EXPECT_EQ(std::count(relaxedInside.begin(), relaxedInside.end(), true), 0);
  // The morph alone leaves some vertices inside (the Poisson carry cuts corners): push-out had work to do.
  const std::vector<bool> morphedInside = pc::insideClosedMesh(body.mesh.V, body.mesh.F, d.dressing.morphed);
  EXPECT_EQ(std::count(morphedInside.begin(), morphedInside.end(), true), d.dressing.pushedVertices);
}

TEST(Dressing, RelaxationShrinksTheSpreadOfAreaRatiosAndConverges) {
  const pcg::Dressing& d = dressedShirt().dressing;
  const pcg::DressingOptions options;
  const double before = log2Quantile(d.areaRatioBefore, 0.95) - log2Quantile(d.areaRatioBefore, 0.05);
  const double after = log2Quantile(d.areaRatioAfter, 0.95) - log2Quantile(d.areaRatioAfter, 0.05);
  EXPECT_LT(after, 0.9 * before) << "5-95% range of log2 area ratio, before " << before << ", after " << after;
  EXPECT_LT(d.relaxIterations, options.maxRelaxIterations);
  EXPECT_GT(d.relaxIterations, 0);
  EXPECT_LT(d.relaxResidual, options.relaxTolerance);
  EXPECT_TRUE(d.relaxConverged);
  EXPECT_EQ(d.summary().find("cap"), std::string::npos) << d.summary();
  // Every free vertex stays on the body, `clearance` outside it.
  const pg::Embedding& e = d.embedding;
  const pg::EmbeddedFrames frames = pg::embeddedFrames(coarseMannequin().mesh.V, coarseMannequin().mesh.F, e);
  const Eigen::MatrixX3d offsets = pg::offsetsFromPositions(frames, d.relaxed);
  for (int v = 0; v < offsets.rows(); ++v) {
    EXPECT_NEAR(offsets.row(v).norm(), options.clearance, 0.5 * options.clearance) << "vertex " << v;
  }
}

TEST(Dressing, EmbeddingIsValidAndOffsetsRoundTrip) {
  const pcg::Dressing& d = dressedShirt().dressing;
  const pb::Body& body = coarseMannequin();
  ASSERT_EQ(d.embedding.size(), tshirt().mesh.numVertices());
  d.embedding.validate(body.mesh.numFaces());
  const pg::EmbeddedFrames frames = pg::embeddedFrames(body.mesh.V, body.mesh.F, d.embedding);
  const Eigen::MatrixX3d offsets = pg::offsetsFromPositions(frames, d.relaxed);
  EXPECT_LT((pg::positionsFromOffsets(frames, offsets) - d.relaxed).cwiseAbs().maxCoeff(), 1e-12);
  // The frame's t follows the pattern's u axis on the dressed surface.
  const Eigen::MatrixX3d u = pcg::patternUDirections(tshirt(), d.relaxed);
  int aligned = 0;
  for (int v = 0; v < u.rows(); ++v) aligned += frames.t.row(v).dot(u.row(v).normalized()) > 0.9;
  EXPECT_GT(aligned, 0.95 * u.rows());
}

TEST(Dressing, UDirectionsAreNotDegenerateAtSideSeams) {
  const pcg::Dressing& d = dressedShirt().dressing;
  const pg::Garment& shirt = tshirt();
  const Eigen::MatrixX3d u = pcg::patternUDirections(shirt, d.relaxed);
  const Eigen::MatrixX3d bodyNormals = pc::vertexNormals(coarseMannequin().mesh.V, coarseMannequin().mesh.F);
  for (const char* seamName : {"side_left", "side_right", "shoulder_left", "underarm_right"}) {
    const pg::Seam* seam = shirt.findSeam(seamName);
    ASSERT_NE(seam, nullptr) << seamName;
    for (int v : seam->vertices) {
      // The u axis of a roughly isometric dressing has about unit length and lies along the surface.
      EXPECT_GT(u.row(v).norm(), 0.35) << seamName << " vertex " << v;
      const Eigen::Vector3d n = bodyNormals.row(coarseMannequin().mesh.F(d.embedding.triangle[v], 0));
      EXPECT_LT(std::abs(u.row(v).normalized().dot(n)), 0.9) << seamName << " vertex " << v;
    }
  }
}

TEST(Dressing, UDirectionsOfTheFlatPatternAreTheUAxis) {
  // Positions = the front layout's UVs in the plane z = 0: every vertex of the front layout sees u = (1, 0, 0), even
  // on the side seams, whose back faces (ignored: first layout only) are folded over by this placement.
  const pg::Garment& shirt = tshirt();
  Eigen::MatrixX3d flat = Eigen::MatrixX3d::Zero(shirt.mesh.numVertices(), 3);
  for (int v = 0; v < flat.rows(); ++v) {
    const int row = shirt.vertexUV(v, 0) >= 0 ? shirt.vertexUV(v, 0) : shirt.vertexUV(v, 1);
    flat.row(v).head<2>() = shirt.mesh.UV.row(row);
  }
  const Eigen::MatrixX3d u = pcg::patternUDirections(shirt, flat);
  for (int v = 0; v < flat.rows(); ++v) {
    if (shirt.vertexUV(v, 0) < 0) continue;
    EXPECT_LT((u.row(v) - Eigen::RowVector3d(1, 0, 0)).norm(), 1e-9) << "vertex " << v;
  }
  EXPECT_FALSE(pixelcloth::testing::inputErrorOf([&] { pcg::patternUDirections(shirt, flat.topRows(10)); }).empty());
}

TEST(Dressing, SleeveVerticesCollideWithTheirArmAndTheHemWithTheTorso) {
  const DressedShirt& d = dressedShirt();
  const pb::Body& body = coarseMannequin();
  auto partName = [&](int v) { return body.parts[d.dressing.part[v]].name; };
  ASSERT_EQ(static_cast<int>(d.dressing.part.size()), tshirt().mesh.numVertices());
  for (int v : d.shirtCage.findCurve("sleeve_hem_left")->vertices) EXPECT_EQ(partName(v), "left_arm") << v;
  for (int v : d.shirtCage.findCurve("sleeve_hem_right")->vertices) EXPECT_EQ(partName(v), "right_arm") << v;
  for (int v : d.shirtCage.findCurve("hem")->vertices) EXPECT_EQ(partName(v), "torso") << v;
}

TEST(Dressing, NecktieKeepsItsRestPlacementPushedOutAndEmbedded) {
  const pb::Body& body = coarseMannequin();
  const pg::Garment tie = pg::makeNecktie();
  const pcg::Dressing d = pcg::dressGarment(body, pcg::bodyCage(body), tie, pcg::garmentCage(tie));
  EXPECT_TRUE(d.cageVertices.empty());
  EXPECT_EQ(d.relaxIterations, 0);
  EXPECT_LT((d.morphed - tie.mesh.V).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((d.relaxed - d.pushed).cwiseAbs().maxCoeff(), 1e-12);
  const std::vector<bool> inside = pc::insideClosedMesh(body.mesh.V, body.mesh.F, d.relaxed);
  EXPECT_EQ(std::count(inside.begin(), inside.end(), true), 0);
  d.embedding.validate(body.mesh.numFaces());
  ASSERT_EQ(d.embedding.size(), tie.mesh.numVertices());
  const pg::EmbeddedFrames frames = pg::embeddedFrames(body.mesh.V, body.mesh.F, d.embedding);
  const Eigen::MatrixX3d offsets = pg::offsetsFromPositions(frames, d.relaxed);
  EXPECT_LT((pg::positionsFromOffsets(frames, offsets) - d.relaxed).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(offsets.col(2).minCoeff(), 0.0);  // the tie hangs in front of the chest, outside the body
  for (int p : d.part) EXPECT_EQ(body.parts[p].name, "torso");
}

TEST(Dressing, PushOutMovesVerticesInsideTheBodyToTheSurface) {
  // The necktie moved 4 cm backwards lies partly inside the chest; push-out brings it back out.
  const pb::Body& body = coarseMannequin();
  pg::Garment tie = pg::makeNecktie();
  tie.mesh.V.col(2).array() -= 0.04;
  const std::vector<bool> insideBefore = pc::insideClosedMesh(body.mesh.V, body.mesh.F, tie.mesh.V);
  ASSERT_GT(std::count(insideBefore.begin(), insideBefore.end(), true), 10);
  const pcg::Dressing d = pcg::dressGarment(body, pcg::bodyCage(body), tie, pcg::garmentCage(tie));
  EXPECT_EQ(d.pushedVertices, std::count(insideBefore.begin(), insideBefore.end(), true));
  EXPECT_GT(d.maxPenetration, 0.0);
  const std::vector<bool> insideAfter = pc::insideClosedMesh(body.mesh.V, body.mesh.F, d.pushed);
  EXPECT_EQ(std::count(insideAfter.begin(), insideAfter.end(), true), 0);
}

TEST(Dressing, RefusesCagesThatDoNotFitTheMeshes) {
  const pb::Body& body = coarseMannequin();
  const pg::Garment& shirt = tshirt();
  const pcg::Cage bodyCage = pcg::bodyCage(body), shirtCage = pcg::garmentCage(shirt);
  const pg::Garment tie = pg::makeNecktie();
  // The necktie's cage on the shirt: its chains do not run along the shirt's edges.
  EXPECT_NE(inputErrorOf([&] { pcg::dressGarment(body, bodyCage, shirt, pcg::garmentCage(tie)); }).find("cage"),
            std::string::npos);
  // The shirt's cage as the body cage: vertex indices beyond the coarse body's.
  EXPECT_NE(inputErrorOf([&] { pcg::dressGarment(body, shirtCage, shirt, shirtCage); }).find("body cage"),
            std::string::npos);
  // Two body junctions swapped: the chest loop's junctions come in an order the shirt's loop cannot follow.
  pcg::Cage swapped = bodyCage;
  const int a = swapped.findNode("centre_front/chest"), b = swapped.findNode("chest/side_left");
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  std::swap(swapped.nodes[a].name, swapped.nodes[b].name);
  EXPECT_NE(inputErrorOf([&] { pcg::dressGarment(body, swapped, shirt, shirtCage); }).find("dressing"),
            std::string::npos);
  pcg::DressingOptions options;
  options.clearance = -0.01;
  EXPECT_NE(inputErrorOf([&] { pcg::dressGarment(body, bodyCage, shirt, shirtCage, options); }).find("clearance"),
            std::string::npos);
}

}  // namespace

TEST(Dressing, ARelaxationStoppedAtItsCapSaysSo) {
  pcg::DressingOptions options;
  options.maxRelaxIterations = 2;
  const pcg::Dressing d =
      pcg::dressGarment(coarseMannequin(), dressedShirt().bodyCage, tshirt(), dressedShirt().shirtCage, options);
  EXPECT_EQ(d.relaxIterations, 2);
  EXPECT_FALSE(d.relaxConverged);
  EXPECT_NE(d.summary().find("2 sweeps, stopped at the cap before settling"), std::string::npos) << d.summary();
}

namespace {

// A garment graded well above or below the body it is dressed on is crumpled or stretched tight: the dressing says
// so and names the grade that would fit; the default T-shirt on the mannequin it was sized for gets no advice.
TEST(Dressing, AGarmentOfTheWrongSizeForItsBodyIsToldTheGradeToTry) {
  const pcg::Dressing& fitting = dressedShirt().dressing;
  EXPECT_GE(fitting.compressedAreaRatio(), pcg::kCompressedAreaRatio);
  EXPECT_LE(fitting.stretchedAreaRatio(), pcg::kStretchedAreaRatio);
  EXPECT_TRUE(pcg::fitAdvice(fitting).empty()) << pcg::fitAdvice(fitting);

  auto dressedAt = [](double grade) {
    pg::TShirtOptions options = pg::TShirtOptions{}.graded(grade);
    options.targetVertices = 1500;
    const pg::Garment shirt = pg::makeTShirt(options);
    return pcg::dressGarment(coarseMannequin(), dressedShirt().bodyCage, shirt, pcg::garmentCage(shirt));
  };
  const pcg::Dressing large = dressedAt(1.35);
  EXPECT_LT(large.compressedAreaRatio(), pcg::kCompressedAreaRatio);
  EXPECT_NEAR(1.35 * pcg::suggestedGrade(large), 1.0, 0.1);  // back to about the size that fits
  std::string advice = pcg::fitAdvice(large);
  for (const char* part : {"too large", "--grade 0.", "--size"}) EXPECT_NE(advice.find(part), std::string::npos) << advice;

  const pcg::Dressing small = dressedAt(0.75);
  EXPECT_GT(small.stretchedAreaRatio(), pcg::kStretchedAreaRatio);
  EXPECT_NEAR(0.75 * pcg::suggestedGrade(small), 1.0, 0.1);
  advice = pcg::fitAdvice(small);
  for (const char* part : {"too small", "--grade 1.", "--size"}) EXPECT_NE(advice.find(part), std::string::npos) << advice;
}

}  // namespace

namespace {

// A garment from another project's origin or up axis is refused before anything is morphed, naming the move.
TEST(Dressing, AGarmentAwayFromTheBodyIsRefusedNamingTheMove) {
  pg::Garment below = tshirt();
  below.mesh.V.col(1).array() -= 1.2;  // its own project's origin, a metre and more below the body
  const std::string message = inputErrorOf(
      [&] { pcg::dressGarment(coarseMannequin(), dressedShirt().bodyCage, below, dressedShirt().shirtCage); });
  EXPECT_NE(message.find("outside the body's bounding box"), std::string::npos) << message;
  EXPECT_NE(message.find("--translate"), std::string::npos) << message;
  EXPECT_EQ(message.find("--up z"), std::string::npos) << message;

  pg::Garment lying = tshirt();  // Z-up: y and z swapped, and far from the body's centre
  lying.mesh.V.col(1).swap(lying.mesh.V.col(2));
  lying.mesh.V.col(0).array() += 2.0;
  const std::string zUp = inputErrorOf(
      [&] { pcg::dressGarment(coarseMannequin(), dressedShirt().bodyCage, lying, dressedShirt().shirtCage); });
  EXPECT_NE(zUp.find("--up z"), std::string::npos) << zUp;
}

}  // namespace
