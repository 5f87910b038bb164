// Base offsets and marker features of a dataset: each row's base is what the reconstructor rebuilds from that row's
// markers, the offsets are those of the final (pushed-out) positions, and the features are the markers' offsets.
#include "pixelcloth/recon/base.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "pixelcloth/data/base_set.h"
#include "pixelcloth/data/dataset.h"
#include "support/recon_fixtures.h"
#include "support/test_util.h"

namespace pb = pixelcloth::body;
namespace pcg = pixelcloth::cage;
namespace pd = pixelcloth::data;
namespace pg = pixelcloth::garment;
namespace pr = pixelcloth::recon;
namespace fs = std::filesystem;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

namespace {

/// A 5-sample dataset of worn shirts (4 train, seed 3), written once per test process.
const fs::path& smallDataset() {
  static const fs::path folder = [] {
    const fs::path f = freshDir("dataset");
    pixelcloth::testing::writeWornDataset(pixelcloth::testing::dressed(), f, 5, 3);
    return f;
  }();
  return folder;
}

}  // namespace

TEST(MarkerFeatures, AreTheMarkersOffsetsInTheirFramesAndZeroWhereDropped) {
  const pixelcloth::testing::Dressed& d = pixelcloth::testing::dressed();
  const pb::Pose pose = pb::randomPose(9, 0.3);
  const Eigen::MatrixX3d truth = d.worn(pose, 0.003);
  const pg::EmbeddedFrames frames = pg::embeddedFrames(d.body.posedVertices(pose), d.body.mesh.F, d.dressing.embedding);
  const Eigen::MatrixX3d offsets = pg::offsetsFromPositions(frames, truth);
  const pcg::MarkerSet captured = pcg::placeMarkers(d.definition, truth, {0, 0.5, 4});
  ASSERT_LT(captured.markers.size(), d.definition.markers.size());
  const Eigen::VectorXd features = pr::markerFeatures(d.definition, captured, frames);
  ASSERT_EQ(features.size(), 3 * static_cast<Eigen::Index>(d.definition.markers.size()));
  size_t next = 0, dropped = 0;
  for (size_t i = 0; i < d.definition.markers.size(); ++i) {
    const pcg::Marker& marker = d.definition.markers[i];
    const Eigen::Vector3d feature = features.segment<3>(3 * i);
    if (next < captured.markers.size() && captured.markers[next].name == marker.name) {
      EXPECT_LT((feature - offsets.row(marker.vertex).transpose()).norm(), 1e-12) << marker.name;
      EXPECT_GT(feature.norm(), 0) << marker.name;
      ++next;
    } else {
      EXPECT_EQ(feature, Eigen::Vector3d::Zero()) << marker.name;
      ++dropped;
    }
  }
  EXPECT_GT(dropped, 0u);

  pcg::MarkerSet reordered = captured;
  std::swap(reordered.markers[0], reordered.markers[1]);
  EXPECT_NE(inputErrorOf([&] { pr::markerFeatures(d.definition, reordered, frames); }).find(captured.markers[0].name),
            std::string::npos);
}

TEST(WriteDatasetBases, EveryRowIsTheReconstructorsRebuildAndItsMarkersOffsets) {
  const pixelcloth::testing::Dressed& d = pixelcloth::testing::dressed();
  const fs::path out = freshDir("bases");
  pr::BaseSetOptions options;
  // A clearance well beyond the worn shirts' gap to the body, so that some vertices are pushed out and the base
  // offsets must be those of the moved positions.
  options.reconstruction.bodyClearance = 0.006;
  const pr::BaseSetReport report = pr::writeDatasetBases(smallDataset(), out, options);
  std::cout << "[bases] " << report.summary() << "\n";
  const pd::Dataset dataset = pd::openDataset(smallDataset());
  const pd::BaseSet base = pd::openBaseSet(out, dataset.info);
  ASSERT_EQ(base.samples, 5);
  ASSERT_EQ(base.markers, static_cast<int>(d.definition.markers.size()));
  EXPECT_EQ(report.markers, base.markers);
  EXPECT_EQ(base.manifest["settings"]["method"], "spline_anisotropic");
  EXPECT_EQ(base.manifest["settings"]["marker_names"].size(), d.definition.markers.size());
  EXPECT_TRUE(base.manifest["settings"]["length_model"].contains("model"));

  // The same rebuild by hand: a reconstructor with the length model fitted on the train rows, markers of each row.
  pr::ReconstructionOptions reconstruction;
  reconstruction.bodyClearance = 0.006;
  pr::GarmentReconstructor reconstructor(d.body, d.garment, d.dressing.embedding, d.dressing.relaxed, reconstruction);
  std::vector<Eigen::MatrixX3d> train;
  for (int r : dataset.rowsOf(pd::Split::Train)) train.push_back(dataset.positionsOf(r).cast<double>());
  ASSERT_EQ(train.size(), 4u);
  reconstructor.setLengthModel(reconstructor.solver().fitLengthModel(d.definition, train, 0.10));
  int pushedOut = 0;
  for (int r = 0; r < dataset.rows(); ++r) {
    SCOPED_TRACE(r);
    const pb::Pose pose = pb::Pose::fromLeading(dataset.pose(r), "pose");
    const Eigen::MatrixX3d truth = dataset.positionsOf(r).cast<double>();
    const pcg::MarkerSet markers = pcg::placeMarkers(d.definition, truth);
    const pr::Reconstruction rec =
        reconstructor.reconstruct(markers, pose, pr::ReconstructionMethod::SplineAnisotropic);
    pushedOut += rec.pushedOut;
    const Eigen::MatrixX3d offsets = base.offsetsOf(r).cast<double>();
    EXPECT_LT((offsets - rec.offsets).cwiseAbs().maxCoeff(), 1e-5);
    // The offsets are those of the final positions: turned back into positions, they are the pushed-out garment.
    const pg::EmbeddedFrames frames =
        pg::embeddedFrames(d.body.posedVertices(pose), d.body.mesh.F, d.dressing.embedding);
    const Eigen::MatrixX3d positions = pg::positionsFromOffsets(frames, offsets);
    EXPECT_LT((positions - rec.positions).rowwise().norm().maxCoeff(), 1e-5);
    EXPECT_LT((positions - truth).rowwise().norm().mean(), 0.02);
    // Exact markers: each feature is the ground-truth offset of its vertex.
    const Eigen::VectorXf features = base.featuresOf(r);
    const Eigen::MatrixX3f truthOffsets = dataset.offsetsOf(r);
    for (size_t i = 0; i < d.definition.markers.size(); ++i)
      EXPECT_LT((features.segment<3>(3 * i) - truthOffsets.row(d.definition.markers[i].vertex).transpose()).norm(),
                1e-5)
          << d.definition.markers[i].name;
  }
  EXPECT_GT(pushedOut, 0) << "no vertex was pushed out: the test does not see which offsets are written";
  EXPECT_LT(report.meanErrorCm, 2.0);
}

TEST(WriteDatasetBases, CapturedMarkersAreSeededPerSampleAndThreadsChangeNothing) {
  const fs::path one = freshDir("one"), two = freshDir("two");
  pr::BaseSetOptions options;
  // Markers 5 cm apart: dropout must not leave a closed curve (a bicep loop has 3 markers at 10 cm) fewer than 3.
  options.markers.spacing = 0.05;
  options.capture = {0.004, 0.2, 11};
  options.reconstruction.spline.markerSigma = 0.004;
  options.lengthModel = pr::LengthModelSource::none();
  pr::writeDatasetBases(smallDataset(), one, options);
  options.threads = 2;
  pr::writeDatasetBases(smallDataset(), two, options);
  const pd::Dataset dataset = pd::openDataset(smallDataset());
  const pd::BaseSet a = pd::openBaseSet(one, dataset.info), b = pd::openBaseSet(two, dataset.info);
  EXPECT_EQ(a.offsets, b.offsets);
  EXPECT_EQ(a.features, b.features);
  EXPECT_EQ(a.manifest["settings"]["length_model"], "none");
  EXPECT_DOUBLE_EQ(a.manifest["settings"]["noise_cm"].get<double>(), 0.4);

  // Dropped markers have zero features, junctions are never dropped, and the samples drop different markers.
  const pixelcloth::testing::Dressed& d = pixelcloth::testing::dressed();
  const pcg::MarkerSet definition = pcg::defineMarkers(d.garment, d.reconstructor->cage(), options.markers);
  ASSERT_EQ(a.markers, static_cast<int>(definition.markers.size()));
  std::vector<std::vector<bool>> droppedOf(dataset.rows());
  for (int r = 0; r < dataset.rows(); ++r) {
    const Eigen::VectorXf features = a.featuresOf(r);
    for (size_t i = 0; i < definition.markers.size(); ++i) {
      const bool zero = features.segment<3>(3 * i).isZero(0);
      if (!definition.markers[i].node.empty()) {
        EXPECT_FALSE(zero) << definition.markers[i].name;
      }
      droppedOf[r].push_back(zero);
    }
    EXPECT_GT(std::count(droppedOf[r].begin(), droppedOf[r].end(), true), 0) << r;
  }
  EXPECT_NE(droppedOf[0], droppedOf[1]);
}

TEST(WriteDatasetBases, RefusesBadOptionsAndFolders) {
  pr::BaseSetOptions options;
  options.threads = -1;
  EXPECT_NE(inputErrorOf([&] { pr::writeDatasetBases(smallDataset(), freshDir("a"), options); }).find("threads"),
            std::string::npos);
  options.threads = 1;
  const fs::path nowhere = freshDir("b") / "nowhere";
  EXPECT_NE(inputErrorOf([&] { pr::writeDatasetBases(nowhere, freshDir("c"), options); }).find("nowhere"),
            std::string::npos);
  // The dataset folder itself is not a place for its bases (they would replace its manifest).
  EXPECT_NE(inputErrorOf([&] { pr::writeDatasetBases(smallDataset(), smallDataset(), options); }).find("manifest"),
            std::string::npos);
  EXPECT_NO_THROW(pd::openDataset(smallDataset()));
}
