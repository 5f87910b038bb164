// The learned worn length of cage segments: a fit reproduces what garments show, the spline uses it, the file
// round-trips, and bad files or models that do not fit the garment are refused with the file's name.
#include "pixelcloth/cage/length_model.h"

#include <gtest/gtest.h>

#include <fstream>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/geodesic.h"
#include "pixelcloth/cage/spline_solver.h"
#include "pixelcloth/core/json_io.h"
#include "support/cage_fixtures.h"
#include "support/test_util.h"

namespace pcg = pixelcloth::cage;
using pixelcloth::testing::inputErrorOf;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }
const pcg::Cage& shirtCage() { return pixelcloth::testing::tshirtCage(); }

/// The template shirt (3D, whose curves are not at their pattern lengths) scaled about its centre.
Eigen::MatrixX3d scaled(double scale) {
  const Eigen::RowVector3d centre = shirt().mesh.V.colwise().mean();
  return (scale * (shirt().mesh.V.rowwise() - centre)).rowwise() + centre;
}

double cageError(const pcg::CageFit& fit, const Eigen::MatrixX3d& truth, const std::vector<int>& vertices) {
  double sum = 0;
  for (int v : vertices) sum += (fit.positions.row(v) - truth.row(v)).norm();
  return sum / vertices.size();
}
}  // namespace

TEST(LengthModel, FitReproducesTheLengthOfASegmentItHasNotSeen) {
  // The shoulder seam has markers at its two ends only: one segment, whose length and chord both scale with the
  // garment, so its points lie on one line through the origin. Without smoothing or shrinkage the fit finds it.
  const pcg::CageSplineSolver solver(shirt(), shirtCage(), {});
  const pcg::MarkerSet definition = pcg::defineMarkers(shirt(), shirtCage());
  pcg::LengthModelOptions options;
  options.smoothingPasses = 0;
  options.shrinkage = 0;
  const pcg::LengthModel model = solver.fitLengthModel(definition, {scaled(0.9), scaled(1.1)}, 0.1, options);
  EXPECT_EQ(model.garment, "tshirt");
  EXPECT_EQ(model.samples, 2);
  EXPECT_EQ(model.curves.size(), shirtCage().curves.size());
  const pcg::CageCurve& shoulder = *shirtCage().findCurve("shoulder_left");
  ASSERT_EQ(model.curves.at("shoulder_left").segments, 2);
  const Eigen::MatrixX3d truth = scaled(1.0);
  const double rest = pcg::patternArcLengths(shirt(), shoulder).back();
  const double chord = (truth.row(shoulder.vertices.front()) - truth.row(shoulder.vertices.back())).norm();
  // (The template's shoulder seam is straight, so the target sits on its floor, 0.01% above the chord.)
  const double length = pcg::curvePolylineLength(truth, shoulder);
  EXPECT_NEAR(model.target("shoulder_left", rest, chord), length, 1.5e-4 * length);
  EXPECT_NEAR(model.curves.at("shoulder_left").intercept + model.curves.at("shoulder_left").slope * chord / rest,
              length / rest, 1e-9);
  // A target is never shorter than the chord.
  EXPECT_GE(model.target("shoulder_left", rest, 10 * chord), 10 * chord);
}

TEST(LengthModel, SplineWithAFittedModelBeatsRestLengthsOnAnUnseenGarment) {
  // The template's curves are longer or shorter than their pattern lengths: rest lengths mislead the spline, a model
  // fitted on scaled copies of the template tells it the worn lengths.
  pcg::CageSplineSolver solver(shirt(), shirtCage(), {});
  const pcg::MarkerSet definition = pcg::defineMarkers(shirt(), shirtCage());
  const pcg::LengthModel model =
      solver.fitLengthModel(definition, {scaled(0.92), scaled(0.97), scaled(1.03), scaled(1.08)}, 0.1);
  const Eigen::MatrixX3d truth = scaled(1.0);
  const pcg::MarkerSet markers = pcg::placeMarkers(definition, truth);
  const double withRest = cageError(solver.solve(markers), truth, solver.cageVertices());
  solver.setLengthModel(model);
  ASSERT_TRUE(solver.lengthModel());
  const pcg::CageFit fit = solver.solve(markers);
  const double withModel = cageError(fit, truth, solver.cageVertices());
  EXPECT_LT(withModel, withRest);
  // Both directions count: every segment is held near its target, here within 5%.
  EXPECT_LT(fit.summary.maxLengthError, 0.05) << fit.summary.summary();
  // The baselines do not use it.
  solver.setLengthModel(std::nullopt);
  EXPECT_FALSE(solver.lengthModel());
}

TEST(LengthModel, JsonRoundTrip) {
  const pcg::CageSplineSolver solver(shirt(), shirtCage(), {});
  const pcg::LengthModel model =
      solver.fitLengthModel(pcg::defineMarkers(shirt(), shirtCage()), {scaled(0.95), scaled(1.05)}, 0.1);
  const auto dir = pixelcloth::testing::freshDir("length_model_json");
  pcg::writeLengthModel(dir / "model.json", model);
  const pcg::LengthModel back = pcg::readLengthModel(dir / "model.json");
  EXPECT_EQ(back.garment, model.garment);
  EXPECT_EQ(back.samples, 2);
  EXPECT_EQ(back.smoothingPasses, model.smoothingPasses);
  EXPECT_DOUBLE_EQ(back.markerSpacing, 0.1);
  ASSERT_EQ(back.curves.size(), model.curves.size());
  for (const auto& [name, line] : model.curves) {
    EXPECT_DOUBLE_EQ(back.curves.at(name).intercept, line.intercept) << name;
    EXPECT_DOUBLE_EQ(back.curves.at(name).slope, line.slope) << name;
    EXPECT_EQ(back.curves.at(name).segments, line.segments) << name;
  }
  EXPECT_NO_THROW(back.validate("tshirt", shirtCage(), "model.json"));
}

TEST(LengthModel, BadFilesAndModelsForAnotherGarmentAreRefusedByName) {
  const auto dir = pixelcloth::testing::freshDir("length_model_bad");
  EXPECT_NE(inputErrorOf([&] { pcg::readLengthModel(dir / "missing.json"); }).find("missing.json"), std::string::npos);
  std::ofstream(dir / "cut.json") << R"({"format": "pixelcloth.length_model", "garment": "tshirt", "curv)";
  EXPECT_NE(inputErrorOf([&] { pcg::readLengthModel(dir / "cut.json"); }).find("cut.json"), std::string::npos);

  const pcg::CageSplineSolver solver(shirt(), shirtCage(), {});
  const nlohmann::json good =
      pcg::toJson(solver.fitLengthModel(pcg::defineMarkers(shirt(), shirtCage()), {scaled(1.0)}, 0.1));
  auto errorOf = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json changed = good;
    edit(changed);
    pixelcloth::core::writeJson(dir / "edited.json", changed);
    return inputErrorOf(
        [&] { pcg::readLengthModel(dir / "edited.json").validate("tshirt", shirtCage(), "edited.json"); });
  };
  std::string e = errorOf([](nlohmann::json& j) { j["curves"]["chest"]["slope"] = "NaN"; });
  EXPECT_NE(e.find("edited.json"), std::string::npos) << e;
  EXPECT_NE(e.find("chest"), std::string::npos) << e;
  e = errorOf([](nlohmann::json& j) { j["curves"].erase("waist"); });
  EXPECT_NE(e.find("waist"), std::string::npos) << e;
  e = errorOf([](nlohmann::json& j) { j["garment"] = "necktie"; });
  EXPECT_NE(e.find("necktie"), std::string::npos) << e;
  e = errorOf([](nlohmann::json& j) { j["format"] = "pixelcloth.markers"; });
  EXPECT_NE(e.find("format"), std::string::npos) << e;

  // Fitting needs garments of the right size.
  EXPECT_NE(inputErrorOf([&] {
              solver.fitLengthModel(pcg::defineMarkers(shirt(), shirtCage()), {}, 0.1);
            }).find("no training"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] {
              solver.fitLengthModel(pcg::defineMarkers(shirt(), shirtCage()), {Eigen::MatrixX3d::Zero(5, 3)}, 0.1);
            }).find("5 rows"),
            std::string::npos);
}
