// The templates' patches: the cage lines split the T-shirt into 14 patches per side and the necktie into bands, each
// small enough for a 160 px crop of the 512 px cloth image.
#include <gtest/gtest.h>

#include <set>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/crop_files.h"
#include "pixelcloth/patches/frame.h"
#include "pixelcloth/patches/patch.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pp = pixelcloth::patches;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;

using pixelcloth::testing::inputErrorOf;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }
/// Every edge of the garment's seams and cage lines (openings are layout boundaries anyway). The same set the cage
/// module's cutEdges gives; built here because patches/ comes before cage/ in the module order.
std::vector<std::pair<int, int>> garmentCuts(const pg::Garment& g) {
  std::vector<std::pair<int, int>> cuts;
  auto add = [&](const std::vector<int>& chain, bool closed) {
    for (size_t i = 0; i + (closed ? 0 : 1) < chain.size(); ++i)
      cuts.emplace_back(chain[i], chain[(i + 1) % chain.size()]);
  };
  for (const auto& seam : g.seams) add(seam.vertices, false);
  for (const auto& line : g.lines) add(line.vertices, line.closed);
  return cuts;
}

const std::vector<pp::Patch>& shirtPatches() {
  static const std::vector<pp::Patch> patches = pp::segmentPatches(shirt(), garmentCuts(shirt()));
  return patches;
}

/// Upper bound on a patch's box, px of the 512 image; see GarmentPatches.TShirtPatchesFitTheCrop.
constexpr double kCropPixels = 160.0;
}  // namespace

TEST(GarmentPatches, TShirtHas14PatchesPerSide) {
  std::vector<int> perLayout(2, 0);
  for (const pp::Patch& p : shirtPatches()) ++perLayout[p.layout];
  EXPECT_EQ(shirtPatches().size(), 28u);
  EXPECT_EQ(perLayout[0], 14);
  EXPECT_EQ(perLayout[1], 14);
}

TEST(GarmentPatches, PatchesCoverEveryFaceOnceAndHaveOneBoundaryLoop) {
  std::vector<int> cover(shirt().mesh.numFaces(), 0);
  for (const pp::Patch& p : shirtPatches()) {
    for (int f : p.faces) ++cover[f];
    // segmentPatches throws unless the boundary is one loop; check it is closed along mesh edges too.
    const pp::PatchMesh mesh = pp::patchMesh(shirt(), p);
    std::set<std::pair<int, int>> edges;
    for (int f = 0; f < mesh.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(mesh.F(f, k), mesh.F(f, (k + 1) % 3)));
    for (size_t i = 0; i < mesh.boundary.size(); ++i)
      EXPECT_TRUE(edges.count(std::minmax(mesh.boundary[i], mesh.boundary[(i + 1) % mesh.boundary.size()])))
          << "patch " << p.id;
    EXPECT_EQ(p.boundary.size() + p.interior.size(), p.vertices.size());
    EXPECT_GT(p.interior.size(), 10u) << "patch " << p.id;
  }
  for (int f = 0; f < shirt().mesh.numFaces(); ++f) ASSERT_EQ(cover[f], 1) << "face " << f;
}

TEST(GarmentPatches, TShirtPatchesFitTheCrop) {
  // DESIGN.md: every patch's box at most 128 px in its side's 512 image, so a 160 px crop holds it with 16 px of
  // context. Measured at the default frame margin: largest ~125 px (the upper-torso patches spanning a torso half).
  double largest = 0;
  for (const pp::Patch& p : shirtPatches()) {
    const Eigen::Vector2d extent = pp::patchPixelExtent(shirt(), p, 512);
    largest = std::max(largest, extent.maxCoeff());
    EXPECT_LE(extent.maxCoeff(), 128.0) << "patch " << p.id;
  }
  RecordProperty("largest_patch_px", std::to_string(largest));
}

TEST(GarmentPatches, NecktieBands) {
  const pg::Garment tie = pg::makeNecktie();
  const std::vector<pp::Patch> patches = pp::segmentPatches(tie, garmentCuts(tie));
  EXPECT_EQ(patches.size(), 5u);
  for (const pp::Patch& p : patches) EXPECT_LE(pp::patchPixelExtent(tie, p, 512).maxCoeff(), 128.0) << p.id;
}

TEST(GarmentPatches, IdsRunInRowsTopToBottomLeftToRight) {
  // Per side: sleeves and upper torso (6), chest to waist (4), waist to hem (4).
  const pg::TShirtOptions o;
  const auto& patches = shirtPatches();
  for (int layout = 0; layout < 2; ++layout) {
    auto box = [&](int k) {
      Eigen::AlignedBox2d b;
      for (int v : patches[14 * layout + k].vertices)
        b.extend(Eigen::Vector2d(shirt().mesh.UV.row(shirt().vertexUV(v, layout))));
      return b;
    };
    for (int k = 0; k < 14; ++k) {
      EXPECT_EQ(patches[14 * layout + k].layout, layout);
      const double top = box(k).max().y();
      if (k < 6) {
        EXPECT_GT(top, o.chestHeight + 0.1) << k;
      } else {
        EXPECT_NEAR(top, k < 10 ? o.chestHeight : o.waistHeight, 1e-12) << k;
      }
      if (k != 0 && k != 6 && k != 10) {
        EXPECT_LT(box(k - 1).center().x(), box(k).center().x()) << k;
      }
    }
  }
}

// Crop folders (`images --crops`, read by `stitch --patches`): they come back as written, and crops of another
// garment or of another patch are refused by their masks and their count, naming the file.
TEST(PatchCropFiles, ComeBackAsWrittenAndCropsOfAnotherGarmentAreRefused) {
  const pg::Garment& g = shirt();
  const auto dir = pixelcloth::testing::freshDir("crop_files");
  const Eigen::MatrixXf offsets = pixelcloth::testing::smoothOffsets(g);
  pp::writePatchCrops(dir / "shirt", pp::garmentCrops(g), offsets);
  const std::vector<pp::PatchCropValues> back = pp::readPatchCrops(dir / "shirt", g);
  ASSERT_EQ(back.size(), 28u);
  for (const pp::PatchCropValues& crop : back)
    for (size_t i = 0; i < crop.vertices.size(); ++i)
      EXPECT_LT((crop.values.row(static_cast<Eigen::Index>(i)) - offsets.row(crop.vertices[i])).norm(), 2e-3);

  // The T-shirt's 28 crops as the necktie's 5.
  const pg::Garment tie = pg::makeNecktie();
  const std::string asTie = inputErrorOf([&] { pp::readPatchCrops(dir / "shirt", tie); });
  EXPECT_NE(asTie.find("another garment"), std::string::npos) << asTie;
  EXPECT_NE(asTie.find("shirt/patch_0"), std::string::npos) << asTie;
  // One patch's crop in another's place.
  std::filesystem::copy_file(dir / "shirt" / "patch_03.exr", dir / "shirt" / "patch_02.exr",
                             std::filesystem::copy_options::overwrite_existing);
  const std::string swapped = inputErrorOf([&] { pp::readPatchCrops(dir / "shirt", g); });
  EXPECT_NE(swapped.find("patch_02.exr: its mask leaves"), std::string::npos) << swapped;
  // An extra crop past the garment's last patch.
  pp::writePatchCrops(dir / "tie", pp::garmentCrops(tie), pixelcloth::testing::smoothOffsets(tie));
  std::filesystem::copy_file(dir / "tie" / "patch_00.exr", dir / "tie" / "patch_05.exr");
  const std::string extra = inputErrorOf([&] { pp::readPatchCrops(dir / "tie", tie); });
  EXPECT_NE(extra.find("patch_05.exr: the necktie has 5 patches"), std::string::npos) << extra;
}
