// Marker sets on the cage (definition, capture noise and dropout, JSON files) and the rest lengths of cage curves
// (pattern, polyline, surface geodesics).
#include "pixelcloth/cage/markers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <set>

#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/geodesic.h"
#include "pixelcloth/core/json_io.h"
#include "support/cage_fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pcg = pixelcloth::cage;
using pixelcloth::testing::inputErrorOf;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }
const pcg::Cage& shirtCage() { return pixelcloth::testing::tshirtCage(); }
void writeText(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }
}  // namespace

TEST(Markers, EveryJunctionAndPointsAlongEachCurveAboutTheSpacingApart) {
  const pcg::MarkerSet set = pcg::defineMarkers(shirt(), shirtCage());
  EXPECT_EQ(set.garment, "tshirt");
  std::set<int> vertices;
  int nodes = 0;
  for (const pcg::Marker& m : set.markers) {
    EXPECT_TRUE(vertices.insert(m.vertex).second) << m.name;
    EXPECT_FALSE(m.hasPosition());
    nodes += m.node.empty() ? 0 : 1;
  }
  EXPECT_EQ(nodes, static_cast<int>(shirtCage().nodes.size()));
  // "A few dozen" markers at 10 cm on a 67 cm shirt; fewer at 20 cm.
  EXPECT_GT(set.markers.size(), 40u);
  EXPECT_LT(set.markers.size(), 200u);
  pcg::MarkerOptions sparse;
  sparse.spacing = 0.2;
  EXPECT_LT(pcg::defineMarkers(shirt(), shirtCage(), sparse).markers.size(), set.markers.size());
  // No gap along a curve is much longer than the spacing.
  for (const pcg::CageCurve& curve : shirtCage().curves) {
    const std::vector<double> s = pcg::patternArcLengths(shirt(), curve);
    double last = -1, gap = 0;
    for (size_t i = 0; i < curve.vertices.size(); ++i) {
      if (!vertices.count(curve.vertices[i])) continue;
      if (last >= 0) gap = std::max(gap, s[i] - last);
      last = s[i];
    }
    EXPECT_LT(gap, 0.16) << curve.name;
  }
  EXPECT_NO_THROW(set.validate(shirt(), shirtCage(), "markers", false));
}

TEST(Markers, CaptureNoiseAndDropoutKeepJunctions) {
  const pcg::MarkerSet definition = pcg::defineMarkers(shirt(), shirtCage());
  const pcg::MarkerSet exact = pcg::placeMarkers(definition, shirt().mesh.V);
  ASSERT_EQ(exact.markers.size(), definition.markers.size());
  for (const pcg::Marker& m : exact.markers) EXPECT_EQ(m.position, Eigen::Vector3d(shirt().mesh.V.row(m.vertex)));
  pcg::CaptureOptions capture;
  capture.noise = 0.01;
  capture.dropout = 0.5;
  capture.seed = 4;
  const pcg::MarkerSet noisy = pcg::placeMarkers(definition, shirt().mesh.V, capture);
  EXPECT_LT(noisy.markers.size(), definition.markers.size());
  int nodes = 0;
  double sum = 0;
  for (const pcg::Marker& m : noisy.markers) {
    nodes += m.node.empty() ? 0 : 1;
    sum += (m.position - Eigen::Vector3d(shirt().mesh.V.row(m.vertex))).squaredNorm();
  }
  EXPECT_EQ(nodes, static_cast<int>(shirtCage().nodes.size()));
  EXPECT_NEAR(std::sqrt(sum / (3 * noisy.markers.size())), 0.01, 0.003);
  // Same seed, same markers.
  EXPECT_EQ(pcg::toJson(pcg::placeMarkers(definition, shirt().mesh.V, capture)), pcg::toJson(noisy));
}

TEST(Markers, JsonRoundTrip) {
  const auto dir = pixelcloth::testing::freshDir("markers");
  const pcg::MarkerSet set = pcg::placeMarkers(pcg::defineMarkers(shirt(), shirtCage()), shirt().mesh.V);
  pcg::writeMarkers(dir / "m.json", set);
  const pcg::MarkerSet back = pcg::readMarkers(dir / "m.json");
  ASSERT_EQ(back.markers.size(), set.markers.size());
  for (size_t i = 0; i < set.markers.size(); ++i) {
    EXPECT_EQ(back.markers[i].name, set.markers[i].name);
    EXPECT_EQ(back.markers[i].vertex, set.markers[i].vertex);
    EXPECT_EQ(back.markers[i].curve, set.markers[i].curve);
    EXPECT_EQ(back.markers[i].node, set.markers[i].node);
    EXPECT_LT((back.markers[i].position - set.markers[i].position).norm(), 1e-12);
  }
  EXPECT_NO_THROW(back.validate(shirt(), shirtCage(), "m.json", true));
}

TEST(Markers, BadInputIsAnInputErrorNamingTheFileAndMarker) {
  const auto dir = pixelcloth::testing::freshDir("bad_markers");
  EXPECT_NE(inputErrorOf([&] { pcg::readMarkers(dir / "missing.json"); }).find("missing.json"), std::string::npos);

  const pcg::MarkerSet set = pcg::placeMarkers(pcg::defineMarkers(shirt(), shirtCage()), shirt().mesh.V);
  nlohmann::json json = pcg::toJson(set);
  // A NaN written by hand (JSON has none: a string or null).
  nlohmann::json nan = json;
  nan["markers"][2]["position"][1] = "NaN";
  writeText(dir / "nan.json", nan.dump());
  const std::string nanError = inputErrorOf([&] { pcg::readMarkers(dir / "nan.json"); });
  EXPECT_NE(nanError.find("nan.json"), std::string::npos) << nanError;
  EXPECT_NE(nanError.find("markers[2]"), std::string::npos) << nanError;
  // A pose file (or any other of ours) given as markers: its format says so.
  nlohmann::json pose = json;
  pose["format"] = "pixelcloth.pose";
  writeText(dir / "pose.json", pose.dump());
  const std::string formatError = inputErrorOf([&] { pcg::readMarkers(dir / "pose.json"); });
  EXPECT_NE(formatError.find("pose.json: format 'pixelcloth.pose', expected 'pixelcloth.markers'"), std::string::npos)
      << formatError;
  writeText(dir / "array.json", "[1, 2, 3]");
  EXPECT_NE(inputErrorOf([&] { pcg::readMarkers(dir / "array.json"); }).find("expected a JSON object"),
            std::string::npos);
  // Without a format (written by hand) it is read.
  nlohmann::json bare = json;
  bare.erase("format");
  writeText(dir / "bare.json", bare.dump());
  EXPECT_EQ(pcg::readMarkers(dir / "bare.json").markers.size(), set.markers.size());

  // Unknown curve, vertex off its curve, wrong garment, node at the wrong vertex.
  auto semanticError = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json changed = json;
    edit(changed);
    writeText(dir / "edited.json", changed.dump());
    return inputErrorOf(
        [&] { pcg::readMarkers(dir / "edited.json").validate(shirt(), shirtCage(), "edited.json", true); });
  };
  int curveMarker = -1;
  for (size_t i = 0; i < set.markers.size() && curveMarker < 0; ++i)
    if (!set.markers[i].curve.empty()) curveMarker = static_cast<int>(i);
  ASSERT_GE(curveMarker, 0);
  std::string e = semanticError([&](nlohmann::json& j) { j["markers"][curveMarker]["curve"] = "collar"; });
  EXPECT_NE(e.find("unknown curve 'collar'"), std::string::npos) << e;
  EXPECT_NE(e.find("edited.json"), std::string::npos) << e;
  const pcg::CageCurve& curve = *shirtCage().findCurve(set.markers[curveMarker].curve);
  int offCurve = 0;
  while (std::find(curve.vertices.begin(), curve.vertices.end(), offCurve) != curve.vertices.end()) ++offCurve;
  e = semanticError([&](nlohmann::json& j) { j["markers"][curveMarker]["vertex"] = offCurve; });
  EXPECT_NE(e.find("not on curve"), std::string::npos) << e;
  e = semanticError([&](nlohmann::json& j) { j["garment"] = "necktie"; });
  EXPECT_NE(e.find("necktie"), std::string::npos) << e;
  e = semanticError([&](nlohmann::json& j) { j["markers"][0]["vertex"] = 1000000; });
  EXPECT_NE(e.find("out of range"), std::string::npos) << e;
  e = semanticError([&](nlohmann::json& j) { j["markers"][0].erase("position"); });
  EXPECT_NE(e.find("no position"), std::string::npos) << e;
}

// ---------------------------------------------------------------------------------------------------------------------
// Rest lengths

TEST(RestLengths, PolylineOfTheFlatPatternEqualsPatternLengthsAndGeodesicsAreNoLonger) {
  // The pattern's own UVs (front layout) as a flat 3D mesh: the polyline along a curve of that layout equals its
  // pattern arc length, and the straight-line geodesic between two of its vertices is no longer than the polyline.
  const auto& g = shirt();
  const pcg::CageCurve& hem = *shirtCage().findCurve("centre_front");
  Eigen::MatrixX3d flat = Eigen::MatrixX3d::Zero(g.mesh.numVertices(), 3);
  std::vector<int> faces;
  for (int f = 0; f < g.mesh.numFaces(); ++f)
    if (g.faceLayout[f] == 0) faces.push_back(f);
  Eigen::MatrixX3i F(faces.size(), 3);
  for (size_t i = 0; i < faces.size(); ++i) {
    F.row(i) = g.mesh.F.row(faces[i]);
    for (int k = 0; k < 3; ++k) flat.row(F(i, k)).head<2>() = g.mesh.UV.row(g.mesh.FUV(faces[i], k));
  }
  const std::vector<double> pattern = pcg::patternArcLengths(g, hem);
  const std::vector<double> polyline = pcg::polylineArcLengths(flat, hem);
  ASSERT_EQ(pattern.size(), polyline.size());
  for (size_t i = 0; i < pattern.size(); ++i) EXPECT_NEAR(pattern[i], polyline[i], 1e-12);

  // The centre line is straight in the pattern: its geodesic equals the polyline (and the chord).
  const pc::GeodesicDistance geodesic(flat, F);
  const int a = hem.vertices.front(), b = hem.vertices.back();
  EXPECT_NEAR(geodesic.between(a, b), polyline.back(), 1e-6 * polyline.back());
  EXPECT_NEAR(geodesic.between(a, b), (flat.row(a) - flat.row(b)).norm(), 1e-9);
  // Along a curved line of the rest shirt in 3D (the neckline), the geodesic between two vertices is never longer
  // than the polyline between them, and not much shorter for close vertices.
  const pcg::CageCurve& neck = *shirtCage().findCurve("neckline");
  const pc::GeodesicDistance rest(g.mesh.V, g.mesh.F);
  const std::vector<double> s = pcg::polylineArcLengths(g.mesh.V, neck);
  for (size_t j : {size_t(1), size_t(3), neck.vertices.size() / 3}) {
    const double d = rest.between(neck.vertices[0], neck.vertices[j]);
    EXPECT_LE(d, s[j] * (1 + 1e-9)) << j;
    EXPECT_GE(d, (g.mesh.V.row(neck.vertices[0]) - g.mesh.V.row(neck.vertices[j])).norm() * (1 - 1e-9)) << j;
  }
  EXPECT_NEAR(rest.between(neck.vertices[0], neck.vertices[1]), s[1], 1e-9);
}
