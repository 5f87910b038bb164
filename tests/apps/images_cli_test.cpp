// pixelcloth images and edit: offsets to cloth images and back; wrong sizes, damaged EXR and NaN refused.
#include "cli_fixtures.h"

namespace pixelcloth::apps {
namespace {

// ---------------------------------------------------------------------------------------------------------------------
// images and edit

/// Smooth centimetre-sized offsets of the default T-shirt, #V x 3.
Eigen::MatrixXf shirtOffsets() {
  static const garment::Garment shirt = garment::makeTShirt();
  Eigen::MatrixXf x(shirt.mesh.numVertices(), 3);
  for (int v = 0; v < x.rows(); ++v) {
    Eigen::Vector3d p = shirt.mesh.V.row(v);
    x.row(v) << 0.02 * std::sin(6 * p.x()), 0.01 * std::cos(5 * p.y()), 0.015 * std::sin(4 * p.x() + 3 * p.y());
  }
  return x;
}

TEST_F(CliTest, ImagesRoundTripThroughExr) {
  fs::path work = dir("work");
  Eigen::MatrixXf x = shirtOffsets();
  core::writeNpy(work / "values.npy", x);
  CliRun run = runPixelcloth(
      {"images", "--garment", "tshirt", "--values", (work / "values.npy").string(), "--out", (work / "img").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(isPng(work / "img" / "cloth.png"));
  core::ExrImage exr = core::readExr(work / "img" / "cloth.exr");
  EXPECT_EQ(exr.width, 256);
  EXPECT_TRUE(exr.hasChannel("front.du") && exr.hasChannel("back.mask"));
  run = runPixelcloth({"images", "--garment", "tshirt", "--image", (work / "img" / "cloth.exr").string(), "--out",
                       (work / "back.npy").string()});
  ASSERT_EQ(run.status, 0) << run;
  Eigen::MatrixXf back = core::readNpyMatrixF(work / "back.npy", x.rows(), 3);
  EXPECT_LT((back - x).cwiseAbs().maxCoeff(), 2e-4);
  EXPECT_TRUE(noTemporaries(work));
}

TEST_F(CliTest, ImagesRefusesWrongVertexCountAndCorruptedExr) {
  fs::path work = dir("work");
  core::writeNpy(work / "few.npy", Eigen::MatrixXf::Zero(10, 3).eval());
  const std::string rows = std::to_string(shirtOffsets().rows());
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--values", (work / "few.npy").string(), "--out",
                                     (work / "img").string()}),
                      {"few.npy", "(10, 3)", "(" + rows + ", 3)"}));
  EXPECT_TRUE(filesUnder(work / "img").empty());
  writeFile(work / "bad.exr", "v/1 this is not an EXR file");
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--image", (work / "bad.exr").string(), "--out",
                                     (work / "v.npy").string()}),
                      {"bad.exr"}));
  EXPECT_FALSE(fs::exists(work / "v.npy"));
}

TEST_F(CliTest, EditShiftWritesExrAndPreview) {
  fs::path work = dir("work");
  core::writeNpy(work / "values.npy", shirtOffsets());
  ASSERT_EQ(runPixelcloth(
                {"images", "--garment", "tshirt", "--values", (work / "values.npy").string(), "--out", work.string()})
                .status,
            0);
  CliRun run = runPixelcloth({"edit", "--image", (work / "cloth.exr").string(), "--out",
                              (work / "shifted.exr").string(), "--shift", "0.01", "0"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(isPng(work / "shifted.png"));
  core::ExrImage before = core::readExr(work / "cloth.exr"), after = core::readExr(work / "shifted.exr");
  Eigen::MatrixXf inside = (before.channel("front.mask").array() > 0).cast<float>();
  EXPECT_NEAR((after.channel("front.du") - before.channel("front.du")).maxCoeff(), 0.01, 1e-6);
  EXPECT_NEAR(
      ((after.channel("front.du") - before.channel("front.du")).array() * (1 - inside.array())).abs().maxCoeff(), 0,
      1e-9);
  EXPECT_EQ(after.channel("front.dn"), before.channel("front.dn"));
  EXPECT_TRUE(refused(runPixelcloth({"edit", "--image", (work / "cloth.exr").string(), "--out",
                                     (work / "x.exr").string(), "--shift", "0.01", "0", "--inflate", "2"}),
                      {"exactly one"}));
  EXPECT_TRUE(refused(runPixelcloth({"edit", "--image", (work / "missing.exr").string(), "--out",
                                     (work / "x.exr").string(), "--inflate", "2"}),
                      {"missing.exr"}));
}

TEST_F(CliTest, ImagesRefusesNanInValuesAndInAnImage) {
  const fs::path work = dir("work");
  Eigen::MatrixXf x = shirtOffsets();
  x(10, 2) = std::numeric_limits<float>::quiet_NaN();
  core::writeNpy(work / "nan.npy", x);
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--values", (work / "nan.npy").string(), "--out",
                                     (work / "img").string()}),
                      {"nan.npy", "row 11, column 3 (counting from 1) is nan"}));
  EXPECT_TRUE(filesUnder(work / "img").empty());

  core::writeNpy(work / "good.npy", shirtOffsets());
  ASSERT_EQ(runPixelcloth({"images", "--garment", "tshirt", "--values", (work / "good.npy").string(), "--out",
                           (work / "good").string()})
                .status,
            0);
  core::ExrImage exr = core::readExr(work / "good" / "cloth.exr");
  for (size_t c = 0; c < exr.channels.size(); ++c)
    if (exr.channelNames[c] == "back.dn") exr.channels[c](7, 20) = std::numeric_limits<float>::infinity();
  core::writeExr(work / "inf.exr", exr);
  EXPECT_TRUE(refused(runPixelcloth({"images", "--garment", "tshirt", "--image", (work / "inf.exr").string(), "--out",
                                     (work / "v.npy").string()}),
                      {"inf.exr", "channel 'back.dn' is inf at row 8, column 21"}));
  EXPECT_FALSE(fs::exists(work / "v.npy"));
}

}  // namespace
}  // namespace pixelcloth::apps
