// The viewer's pieces: cage curves and their measure, each vertex's patch, and the site's refusals. The pages
// themselves are opened in Chromium by tests/apps/view_cli_test.cpp.
#include "pixelcloth/viz/viewer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>

#include "pixelcloth/core/error.h"
#include "pixelcloth/patches/patch.h"
#include "support/test_util.h"

namespace pv = pixelcloth::viz;
namespace fs = std::filesystem;

TEST(Viewer, CurvesMeasureTheirFoldAgainstGroundTruthAndEveryVertexHasItsPatch) {
  const pixelcloth::garment::Garment tie = pixelcloth::garment::makeNecktie();
  const Eigen::MatrixX3d flat = tie.mesh.V;
  // The same shape as ground truth: no jump anywhere.
  const std::vector<pv::ViewCurve> same = pv::viewCurves(tie, flat, &flat);
  ASSERT_FALSE(same.empty());
  const pv::ViewCurve* inside = nullptr;  // a curve with triangles on both sides
  for (const pv::ViewCurve& curve : same) {
    EXPECT_GE(curve.vertices.size(), 2u) << curve.name;
    if (std::isfinite(curve.normalJumpDeg)) {
      EXPECT_NEAR(curve.normalJumpDeg, 0, 1e-9) << curve.name;
      inside = &curve;
    }
  }
  ASSERT_TRUE(inside) << "no curve with two-sided edges";
  // Folded along that curve's height (the tie's cage lines run across it): that curve folds.
  double middle = 0;
  for (int v : inside->vertices) middle += flat(v, 1) / inside->vertices.size();
  Eigen::MatrixX3d folded = flat;
  for (Eigen::Index v = 0; v < folded.rows(); ++v)
    if (flat(v, 1) < middle) folded(v, 2) += 0.8 * (middle - flat(v, 1));
  double largest = 0;
  for (const pv::ViewCurve& curve : pv::viewCurves(tie, folded, &flat))
    if (std::isfinite(curve.normalJumpDeg)) largest = std::max(largest, curve.normalJumpDeg);
  EXPECT_GT(largest, 1.0);

  const Eigen::VectorXi patch = pv::patchOfVertex(tie);
  ASSERT_EQ(patch.size(), tie.mesh.numVertices());
  const std::vector<pixelcloth::patches::Patch> patches = pixelcloth::patches::garmentPatches(tie);
  EXPECT_EQ(std::set<int>(patch.data(), patch.data() + patch.size()).size(), patches.size());
  for (const pixelcloth::patches::Patch& p : patches)
    for (int v : p.vertices) EXPECT_LE(patch(v), p.id);
}

TEST(Viewer, WithoutThreeJsOrScenesNothingIsWritten) {
  const fs::path dir = pixelcloth::testing::freshDir("viewer"), site = dir / "site";
  pv::ViewSite empty{"nothing", "nowhere", {}};
  EXPECT_THROW(pv::writeViewSite(site, empty), pixelcloth::core::InputError);
  EXPECT_FALSE(fs::exists(site));

  pv::ViewScene scene;
  scene.name = "a triangle";
  scene.garmentFaces = Eigen::MatrixX3i(1, 3);
  scene.garmentFaces << 0, 1, 2;
  scene.garments.push_back({"garment", false, {Eigen::MatrixX3d::Identity(3, 3)}, {}});
  const pv::ViewSite one{"one", "here", {scene}};
  const char* before = std::getenv("PIXELCLOTH_THREE_DIR");
  const std::string saved = before ? before : "";
  ::setenv("PIXELCLOTH_THREE_DIR", dir.c_str(), 1);  // holds no three.js
  try {
    pv::writeViewSite(site, one);
    ADD_FAILURE() << "written without three.js";
  } catch (const pixelcloth::core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("libjs-three"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("three.min.js"), std::string::npos) << e.what();
  }
  if (before)
    ::setenv("PIXELCLOTH_THREE_DIR", saved.c_str(), 1);
  else
    ::unsetenv("PIXELCLOTH_THREE_DIR");
  EXPECT_FALSE(fs::exists(site));
}
