// The seam metrics on the built-in T-shirt: ground truth stitched from its own crops has no gap and no jump, a step
// across one curve shows on that curve alone, and a smooth bend that ground truth shares is not counted.
#include "pixelcloth/stitch/seams.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "pixelcloth/core/mesh.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/patch.h"
#include "support/fixtures.h"

namespace {

namespace ps = pixelcloth::stitch;
namespace pp = pixelcloth::patches;
using pixelcloth::testing::tshirt;

/// The vertices each patch decoder predicts (its enlarged crop), per patch.
const std::vector<std::vector<int>>& cropVertices() {
  static const std::vector<std::vector<int>> crops = [] {
    std::vector<std::vector<int>> out;
    for (const pp::Patch& patch : pp::garmentPatches(tshirt())) out.push_back(pp::enlargedCrop(tshirt(), patch).sample.vertices);
    return out;
  }();
  return crops;
}

/// Every crop's predictions taken from `positions`.
std::vector<ps::PredictedPositions> cropsOf(const Eigen::MatrixX3d& positions) {
  std::vector<ps::PredictedPositions> out;
  for (const std::vector<int>& vertices : cropVertices()) {
    ps::PredictedPositions p{&vertices, Eigen::MatrixX3d(vertices.size(), 3)};
    for (size_t i = 0; i < vertices.size(); ++i) p.positions.row(i) = positions.row(vertices[i]);
    out.push_back(std::move(p));
  }
  return out;
}

const nlohmann::json& curveOf(const nlohmann::json& metrics, const std::string& name) {
  for (const nlohmann::json& c : metrics["curves"])
    if (c["name"] == name) return c;
  ADD_FAILURE() << "no curve " << name;
  return metrics;
}

TEST(Seams, GroundTruthStitchedFromItsOwnCropsHasNoGapAndNoJump) {
  const ps::SeamLayout layout(tshirt());
  ps::SeamMetrics metrics(layout);
  const Eigen::MatrixX3d truth = tshirt().mesh.V;
  metrics.add(cropsOf(truth), truth, truth);
  const nlohmann::json json = metrics.toJson();
  EXPECT_EQ(json["samples"], 1);
  EXPECT_DOUBLE_EQ(json["gap_cm"]["max"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(json["normal_jump_deg"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(json["near_seam_error_cm"].get<double>(), 0.0);
  // The crops overlap around every curve patches meet across: each such curve has vertices predicted twice.
  const nlohmann::json& side = curveOf(json, "side_left");
  EXPECT_GT(side["shared_vertices"].get<int>(), 10);
  EXPECT_EQ(side["shared_vertices"], side["vertices"]);
  EXPECT_GT(layout.nearSeam().size(), 100u);
  EXPECT_GT(layout.interior().size(), 100u);
}

TEST(Seams, TheGapIsTheDistanceBetweenTwoPredictionsOfAVertex) {
  const ps::SeamLayout layout(tshirt());
  ps::SeamMetrics metrics(layout);
  const Eigen::MatrixX3d truth = tshirt().mesh.V;
  std::vector<ps::PredictedPositions> crops = cropsOf(truth);
  crops[0].positions.col(2).array() += 0.01;  // patch 0 predicts everything 1 cm further forward
  metrics.add(crops, truth, truth);
  const nlohmann::json json = metrics.toJson();
  EXPECT_NEAR(json["gap_cm"]["max"].get<double>(), 1.0, 1e-9);
  std::set<int> zero(cropVertices()[0].begin(), cropVertices()[0].end());
  for (const nlohmann::json& c : json["curves"]) {
    const ps::SeamCurve* curve = nullptr;
    for (const ps::SeamCurve& s : layout.curves())
      if (s.name == c["name"]) curve = &s;
    ASSERT_NE(curve, nullptr);
    const bool touches = std::any_of(curve->vertices.begin(), curve->vertices.end(), [&](int v) { return zero.count(v); });
    if (!touches && c["gap_cm"]["max"].is_number()) {
      EXPECT_DOUBLE_EQ(c["gap_cm"]["max"].get<double>(), 0.0) << c["name"];
    }
  }
}

// One garment's seam gap (a frame of a sequence): 0 for agreeing crops; with patch 0 1 cm off, 1 cm on the curve
// vertices it shares and 0 on the others, so the mean lies strictly between; NaN for a single whole-garment prediction.
TEST(Seams, TheSeamGapOfOneGarmentIsTheMeanGapOverSharedCurveVertices) {
  const ps::SeamLayout layout(tshirt());
  const Eigen::MatrixX3d truth = tshirt().mesh.V;
  std::vector<ps::PredictedPositions> crops = cropsOf(truth);
  EXPECT_DOUBLE_EQ(ps::meanSeamGapCm(layout, crops), 0.0);
  crops[0].positions.col(2).array() += 0.01;
  const std::set<int> zero(cropVertices()[0].begin(), cropVertices()[0].end());
  std::vector<int> count(truth.rows(), 0);
  for (const std::vector<int>& crop : cropVertices())
    for (int v : crop) ++count[v];
  int shared = 0, moved = 0;
  for (int v : layout.cageVertices())
    if (count[v] >= 2) {
      ++shared;
      moved += static_cast<int>(zero.count(v));
    }
  ASSERT_GT(moved, 0);
  EXPECT_NEAR(ps::meanSeamGapCm(layout, crops), static_cast<double>(moved) / shared, 1e-9);
  std::vector<int> all(truth.rows());
  for (int v = 0; v < static_cast<int>(all.size()); ++v) all[v] = v;
  EXPECT_TRUE(std::isnan(ps::meanSeamGapCm(layout, {{&all, truth}})));
}

TEST(Seams, AStepAcrossOneCurveJumpsThereAndASharedSmoothBendDoesNot) {
  const pixelcloth::garment::Garment& shirt = tshirt();
  const ps::SeamLayout layout(shirt);
  const ps::SeamCurve* side = nullptr;
  for (const ps::SeamCurve& c : layout.curves())
    if (c.name == "side_left") side = &c;
  ASSERT_NE(side, nullptr);
  ASSERT_GT(side->facePairs.size(), 5u);
  // The step: the front's vertices one ring off the curve pushed 1 cm out along the surface normal.
  const Eigen::MatrixX3d truth = shirt.mesh.V;
  const Eigen::MatrixX3d normals = pixelcloth::core::vertexNormals(truth, shirt.mesh.F);
  const std::set<int> onCurve(side->vertices.begin(), side->vertices.end());
  const int front = shirt.layoutIndex("front");
  std::set<int> ring;
  for (Eigen::Index f = 0; f < shirt.mesh.F.rows(); ++f) {
    if (shirt.faceLayout(f) != front) continue;
    bool touches = false;
    for (int c = 0; c < 3; ++c) touches = touches || onCurve.count(shirt.mesh.F(f, c));
    if (touches)
      for (int c = 0; c < 3; ++c)
        if (!onCurve.count(shirt.mesh.F(f, c))) ring.insert(shirt.mesh.F(f, c));
  }
  Eigen::MatrixX3d stepped = truth;
  for (int v : ring) stepped.row(v) += 0.01 * normals.row(v);
  ps::SeamMetrics step(layout);
  step.add({}, stepped, truth);
  const nlohmann::json json = step.toJson();
  EXPECT_GT(curveOf(json, "side_left")["normal_jump_deg"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(curveOf(json, "side_right")["normal_jump_deg"].get<double>(), 0.0);
  EXPECT_TRUE(json["gap_cm"]["mean"].is_null());  // no separate predictions given

  // A smooth bend of the whole shirt (about the vertical axis, angle growing with height), in both the prediction and
  // ground truth: the fold angles change, the jump stays zero.
  Eigen::MatrixX3d bent = truth;
  for (Eigen::Index v = 0; v < bent.rows(); ++v) {
    const double a = 0.8 * bent(v, 1), c = std::cos(a), s = std::sin(a);
    const double x = bent(v, 0), z = bent(v, 2);
    bent(v, 0) = c * x + s * z;
    bent(v, 2) = -s * x + c * z;
  }
  const Eigen::MatrixX3d nRest = pixelcloth::core::faceNormals(truth, shirt.mesh.F),
                         nBent = pixelcloth::core::faceNormals(bent, shirt.mesh.F);
  double change = 0;
  for (const auto& pair : side->facePairs) change += std::abs(ps::foldAngleDeg(nBent, pair) - ps::foldAngleDeg(nRest, pair));
  EXPECT_GT(change / side->facePairs.size(), 0.01);
  ps::SeamMetrics shared(layout);
  shared.add(cropsOf(bent), bent, bent);
  EXPECT_NEAR(shared.toJson()["normal_jump_deg"].get<double>(), 0.0, 1e-9);
}

}  // namespace
