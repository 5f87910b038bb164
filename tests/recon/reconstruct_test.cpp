// Garments from markers: the posed body keeps rebuilt vertices out of it; every method passes through its markers and
// rebuilds a worn shirt; the dataset evaluation writes its metrics and meshes.
#include "pixelcloth/recon/reconstruct.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "support/fixtures.h"
#include "support/recon_fixtures.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace pb = pixelcloth::body;
namespace pg = pixelcloth::garment;
namespace pr = pixelcloth::recon;

TEST(PosedBody, PushesPointsInsideOutToTheClearanceAndLeavesTheOthers) {
  const pb::Body& body = pixelcloth::testing::coarseMannequin();
  const pb::Pose pose = pb::Pose::identity();
  const Eigen::MatrixX3d V = body.posedVertices(pose);
  const Eigen::MatrixX3d N = pc::vertexNormals(V, body.mesh.F);
  const pr::PosedBody posed(V, body.mesh.F, pg::EmbeddedFrames{});
  // Every 10th body vertex, 5 mm inside and 5 cm outside.
  std::vector<int> picked;
  for (int v = 0; v < V.rows(); v += 10) picked.push_back(v);
  const int n = static_cast<int>(picked.size());
  Eigen::MatrixX3d inside(n, 3), outside(n, 3);
  for (int i = 0; i < n; ++i) {
    inside.row(i) = V.row(picked[i]) - 0.005 * N.row(picked[i]);
    outside.row(i) = V.row(picked[i]) + 0.05 * N.row(picked[i]);
  }
  const double clearance = 0.001;
  Eigen::MatrixX3d moved = inside;
  EXPECT_EQ(posed.pushOut(moved, clearance), n);
  int near = 0;
  for (int i = 0; i < n; ++i) {
    // Out along about the normal it went in by: 1 mm outside its vertex (the surface curves a little between
    // vertices 2 cm apart).
    const Eigen::RowVector3d target = V.row(picked[i]) + clearance * N.row(picked[i]);
    near += (moved.row(i) - target).norm() < 0.002 ? 1 : 0;
    EXPECT_GT((moved.row(i) - V.row(picked[i])).dot(N.row(picked[i])), -0.001) << picked[i];
  }
  EXPECT_GT(near, 0.9 * n);
  // Where they went is clear of the body: a second push hardly moves them (in a crease, where a point pushed off one
  // side comes near the other, by at most about the clearance).
  Eigen::MatrixX3d again = moved;
  posed.pushOut(again, clearance);
  const Eigen::VectorXd second = (again - moved).rowwise().norm();
  EXPECT_LT(second.maxCoeff(), 1.5 * clearance);
  EXPECT_LT((second.array() > 1e-4).count(), 0.02 * n);
  Eigen::MatrixX3d far = outside;
  EXPECT_EQ(posed.pushOut(far, clearance), 0);
  EXPECT_EQ(far, outside);
}

// ---------------------------------------------------------------------------------------------------------------------
// The reconstruction as a library: markers -> spline cage -> fill -> clearance, and its evaluation on a dataset.

namespace {

namespace fs = std::filesystem;
namespace pcg = pixelcloth::cage;
namespace pd = pixelcloth::data;

using pixelcloth::testing::Dressed;
using pixelcloth::testing::dressed;

/// Mean distance between rows of `a` and `b` over `rows` (all rows when empty).
double meanError(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, const std::vector<int>& rows = {}) {
  if (rows.empty()) return (a - b).rowwise().norm().mean();
  double sum = 0;
  for (int r : rows) sum += (a.row(r) - b.row(r)).norm();
  return sum / rows.size();
}

std::vector<int> cageVertices(const pcg::Cage& cage) {
  std::set<int> vertices;
  for (const pcg::CageCurve& curve : cage.curves) vertices.insert(curve.vertices.begin(), curve.vertices.end());
  return {vertices.begin(), vertices.end()};
}

}  // namespace

TEST(GarmentReconstructor, EveryMethodPassesThroughTheMarkersAndRebuildsAWornShirt) {
  const Dressed& d = dressed();
  const pb::Pose pose = pb::randomPose(3, 0.3);
  const Eigen::MatrixX3d truth = d.worn(pose, 0.004);
  const pcg::MarkerSet markers = pcg::placeMarkers(d.definition, truth);
  // The spline holds its segments to worn lengths learned from other shapes of the same shirt (other poses).
  pr::GarmentReconstructor reconstructor(d.body, d.garment, d.dressing.embedding, d.dressing.relaxed);
  std::vector<Eigen::MatrixX3d> training;
  for (int k = 0; k < 6; ++k) training.push_back(d.worn(pb::randomPose(20 + k, 0.3), 0.002 + 0.001 * k));
  reconstructor.setLengthModel(
      reconstructor.solver().fitLengthModel(d.definition, training, pcg::MarkerOptions{}.spacing, {}));
  const std::vector<int> cage = cageVertices(reconstructor.cage());
  std::map<pr::ReconstructionMethod, double> cageError;
  for (pr::ReconstructionMethod method : pr::allReconstructionMethods()) {
    SCOPED_TRACE(pr::reconstructionMethodName(method));
    const pr::Reconstruction rec = reconstructor.reconstruct(markers, pose, method);
    ASSERT_EQ(rec.positions.rows(), truth.rows());
    ASSERT_TRUE(rec.positions.allFinite());
    // The curves pass through their markers (the clearance may move a marker that is nearer the body than 1 mm).
    for (const pcg::Marker& marker : markers.markers)
      EXPECT_LT((rec.cage.row(marker.vertex).transpose() - marker.position).norm(), 1e-4) << marker.name;
    cageError[method] = meanError(rec.cage, truth, cage);
    std::cout << "[" << pr::reconstructionMethodName(method) << "] cage " << 100 * cageError[method] << " cm, garment "
              << 100 * meanError(rec.positions, truth) << " cm\n";
    EXPECT_LT(cageError[method], 0.01);
    EXPECT_LT(meanError(rec.positions, truth), 0.02);
  }
  // Between markers about 10 cm apart on a smooth shirt, the curves beat straight lines.
  EXPECT_LT(cageError[pr::ReconstructionMethod::Spline], cageError[pr::ReconstructionMethod::Linear]);
  EXPECT_LT(cageError[pr::ReconstructionMethod::CatmullRom], cageError[pr::ReconstructionMethod::Linear]);
}

TEST(GarmentReconstructor, FillFromTheTrueCageReproducesASmoothShirt) {
  const Dressed& d = dressed();
  const pb::Pose pose = pb::randomPose(5, 0.3);
  const Eigen::MatrixX3d truth = d.worn(pose, 0.0);
  const pr::PosedBody posed = d.reconstructor->posed(pose);
  for (bool anisotropic : {false, true}) {
    const pr::Reconstruction rec = d.reconstructor->fillFromCage(truth, posed, anisotropic);
    // The dressed shirt's offsets vary slowly between cage curves, so harmonic interiors are close to them.
    EXPECT_LT(meanError(rec.positions, truth), 0.005) << (anisotropic ? "anisotropic" : "isotropic");
  }
}

TEST(GarmentReconstructor, RefusesMarkersOfAnotherGarment) {
  const Dressed& d = dressed();
  pcg::MarkerSet markers = pcg::placeMarkers(d.definition, d.dressing.relaxed);
  markers.garment = "necktie";
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] {
              d.reconstructor->reconstruct(markers, pb::Pose::identity());
            }).find("necktie"),
            std::string::npos);
}

TEST(ReconstructDataset, WritesMetricsForEveryMethodAndTheFirstMeshes) {
  const Dressed& d = dressed();
  const fs::path folder = pixelcloth::testing::freshDir("dataset"), out = pixelcloth::testing::freshDir("out");
  pixelcloth::testing::writeWornDataset(d, folder, 10, 3);
  pr::DatasetReconstructionOptions options;
  options.split.reset();  // every row
  options.meshes = 1;
  const pr::DatasetReconstructionReport report = pr::reconstructDataset(folder, out, options);
  EXPECT_EQ(report.samples, 10);
  ASSERT_EQ(report.meanVertexError.size(), pr::allReconstructionMethods().size());
  for (pr::ReconstructionMethod method : pr::allReconstructionMethods()) {
    const nlohmann::json& m = report.metrics["methods"][pr::reconstructionMethodName(method)];
    EXPECT_GT(m["cage_cm"].get<double>(), 0.0);
    EXPECT_LT(m["garment_cm"].get<double>(), 2.0);
  }
  EXPECT_LT(report.metrics["methods"]["spline"]["cage_cm"].get<double>(),
            report.metrics["methods"]["linear"]["cage_cm"].get<double>());
  for (const char* file :
       {"metrics.json", "markers.json", "length_model.json", "sample_000000/truth.obj", "sample_000000/spline.obj"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  EXPECT_FALSE(fs::exists(out / "sample_000001"));
  // The rebuilt mesh on disk is the one measured: its error against the truth is its method's error of that sample.
  const pc::Mesh truth = pc::readMesh(out / "sample_000000" / "truth.obj");
  EXPECT_EQ(truth.numVertices(), d.garment.mesh.numVertices());

  // One split: its rows alone, named in the metrics.
  options.split = pixelcloth::data::Split::Test;
  const pr::DatasetReconstructionReport test =
      pr::reconstructDataset(folder, pixelcloth::testing::freshDir("test"), options);
  EXPECT_GE(test.samples, 1);
  EXPECT_LT(test.samples, 10);
  EXPECT_EQ(test.metrics["split"], "test");
}
