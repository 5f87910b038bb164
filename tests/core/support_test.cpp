// Errors, atomic writes, progress, PNG pictures and topology checks: the support every module uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/image.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/progress.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace fs = std::filesystem;

TEST(Error, CheckThrowsInputErrorWithMessageAndLocation) {
  try {
    int found = 7;
    PIXELCLOTH_CHECK(found == 3, "thing.obj: expected 3, found " << found);
    FAIL() << "no exception";
  } catch (const pc::InputError& e) {
    EXPECT_STREQ(e.what(), "thing.obj: expected 3, found 7");
    EXPECT_NE(e.where().find("support_test.cpp:"), std::string::npos);
  }
}

TEST(Error, AssertThrowsInternalErrorThatSaysItIsABug) {
  try {
    const int rows = 4;
    PIXELCLOTH_ASSERT(rows == 3, "solver: " << rows << " rows");
    FAIL() << "no exception";
  } catch (const pc::InputError&) {
    FAIL() << "an internal failure must not look like bad input (exit 2)";
  } catch (const pc::InternalError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bug"), std::string::npos) << message;
    EXPECT_NE(message.find("support_test.cpp:"), std::string::npos) << message;
    EXPECT_NE(message.find("'rows == 3' failed: solver: 4 rows"), std::string::npos) << message;
  }
}

TEST(Log, WarningsShowUnderQuietButNotUnderSilent) {
  const pc::LogLevel before = pc::logLevel();
  for (const auto& [level, shown] : {std::pair{pc::LogLevel::Warning, true}, std::pair{pc::LogLevel::Quiet, false}}) {
    pc::setLogLevel(level);
    ::testing::internal::CaptureStderr();
    PIXELCLOTH_WARN("writer: 3 samples dropped");
    PIXELCLOTH_INFO("progress that quiet hides");
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(err, shown ? "warning: writer: 3 samples dropped\n" : "");
  }
  pc::setLogLevel(before);
}

TEST(AtomicFile, FailedWriterLeavesNothingBehind) {
  fs::path dir = pixelcloth::testing::freshDir("atomic");
  fs::path target = dir / "out.txt";
  EXPECT_THROW(pc::writeAtomically(target,
                                   [](const fs::path& tmp) {
                                     std::ofstream(tmp) << "half";
                                     throw pc::InputError("boom");
                                   }),
               pc::InputError);
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::is_empty(dir));
  pc::writeTextAtomically(target, "whole");
  EXPECT_EQ(pc::readTextFile(target), "whole");
  EXPECT_TRUE(fs::exists(target));
}

TEST(AtomicFile, MissingFileIsNamed) {
  try {
    pc::readTextFile("/nonexistent/dir/file.json");
    FAIL();
  } catch (const pc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/file.json: no such file"), std::string::npos);
  }
}

TEST(AtomicFile, OutputFolderThatIsAFileIsRefused) {
  fs::path dir = pixelcloth::testing::freshDir("outfolder");
  pc::writeTextAtomically(dir / "file", "x");
  EXPECT_THROW(pc::ensureOutputFolder(dir / "file"), pc::InputError);
}

TEST(Progress, LineShowsCountRateAndEta) {
  pc::Progress progress("simulate", 10);
  progress.advance(4);
  std::string line = progress.line();
  EXPECT_NE(line.find("simulate"), std::string::npos);
  EXPECT_NE(line.find("4/10"), std::string::npos);
  EXPECT_NE(line.find("40%"), std::string::npos);
  EXPECT_NE(line.find("/s"), std::string::npos);
  EXPECT_NE(line.find("ETA"), std::string::npos);
  EXPECT_EQ(pc::formatDuration(75), "1:15");
  EXPECT_EQ(pc::formatDuration(3725), "1:02:05");
}

TEST(Png, RoundTripAndCorruption) {
  fs::path dir = pixelcloth::testing::freshDir("png");
  pc::RgbImage image(37, 21, {10, 20, 30});
  for (int x = 2; x < 30; ++x) image.set(x, x / 2, {250, 0, 0});
  image.blend(5, 17, {0, 0, 255}, 0.4);
  pc::writePng(dir / "a.png", image);
  pc::RgbImage back = pc::readPng(dir / "a.png");
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 21);
  EXPECT_EQ(back.pixels, image.pixels);
  // A truncated file is reported, not half-read.
  std::string bytes = pc::readTextFile(dir / "a.png");
  pc::writeTextAtomically(dir / "cut.png", bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(pc::readPng(dir / "cut.png"), pc::InputError);
  pc::writeTextAtomically(dir / "text.png", "hello, not a png");
  EXPECT_THROW(pc::readPng(dir / "text.png"), pc::InputError);
}

TEST(Topology, ClosedTetrahedronAndItsFaults) {
  Eigen::MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixX3i F(4, 3);
  F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  pc::TopologyReport closed = pc::checkTopology(4, F);
  EXPECT_TRUE(closed.closedManifold()) << closed.firstProblem;
  EXPECT_EQ(closed.components, 1);
  EXPECT_NEAR(pc::enclosedVolume(V, F), 1.0 / 6.0, 1e-12);

  pc::TopologyReport open = pc::checkTopology(4, F.topRows(3));
  EXPECT_FALSE(open.closedManifold());
  EXPECT_EQ(open.boundaryEdges, 3);
  EXPECT_NE(open.firstProblem.find("boundary"), std::string::npos);

  Eigen::MatrixX3i flipped = F;
  std::swap(flipped(0, 1), flipped(0, 2));
  EXPECT_GT(pc::checkTopology(4, flipped).inconsistentEdges, 0);
}

TEST(Topology, ComponentsAreRankedBySizeAndTheProblemsOneNamed) {
  // A closed tetrahedron (vertices 1-4, counted from 1) and a lone triangle (vertices 5-7): two components.
  pc::Mesh mesh;
  mesh.V.resize(7, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 5, 5, 6, 5, 5, 5, 6, 5;
  mesh.F.resize(5, 3);
  mesh.F << 4, 5, 6, 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  mesh.vertexAttributes["w"] = Eigen::VectorXd::LinSpaced(7, 0, 6);
  mesh.faceAttributes["id"] = Eigen::VectorXi::LinSpaced(5, 0, 4);
  const pc::TopologyReport report = pc::checkTopology(7, mesh.F);
  EXPECT_EQ(report.components, 2);
  EXPECT_EQ(report.componentFaces, (std::vector<int>{4, 1}));
  EXPECT_EQ(report.boundaryEdges, 3);
  EXPECT_EQ(report.firstProblemComponent, 2);  // the triangle's edges are the open ones
  // Its vertices are 5 to 7 counted from 1 (4 to 6 from 0).
  EXPECT_TRUE(std::regex_search(report.firstProblem, std::regex("edge \\([567], [567]\\)"))) << report.firstProblem;
  EXPECT_EQ(pc::faceComponents(7, mesh.F), (std::vector<int>{1, 0, 0, 0, 0}));

  const pc::Mesh kept = pc::largestComponent(mesh);
  ASSERT_EQ(kept.numVertices(), 4);
  ASSERT_EQ(kept.numFaces(), 4);
  EXPECT_TRUE(pc::checkTopology(4, kept.F).closedManifold());
  EXPECT_EQ(kept.V, mesh.V.topRows(4));
  EXPECT_EQ(kept.F, mesh.F.bottomRows(4));
  EXPECT_EQ(kept.vertexAttributes.at("w"), Eigen::VectorXd::LinSpaced(4, 0, 3));
  EXPECT_EQ(kept.faceAttributes.at("id"), Eigen::VectorXi::LinSpaced(4, 1, 4));
}

TEST(Mesh, ValidateNamesTheFault) {
  pc::Mesh mesh;
  mesh.V = Eigen::MatrixX3d::Zero(3, 3);
  mesh.V(1, 0) = 1;
  mesh.V(2, 1) = 1;
  mesh.F.resize(1, 3);
  mesh.F << 0, 1, 5;
  try {
    mesh.validate("garment.obj");
    FAIL();
  } catch (const pc::InputError& e) {
    EXPECT_STREQ(e.what(), "garment.obj: face 1 uses vertex 6, but the mesh has 3 vertices");  // counted from 1
  }
  mesh.F << 0, 1, 2;
  mesh.V(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mesh.validate("x"), pc::InputError);
}

TEST(Mesh, ClosestPointOnTriangleBeatsDenseSampling) {
  // Random points against random triangles: the exact closest point is never further than the best of a dense
  // barycentric grid, and lies on the triangle (coordinates >= 0, sum 1).
  std::srand(3);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a = Eigen::Vector3d::Random(), b = Eigen::Vector3d::Random(), c = Eigen::Vector3d::Random();
    const Eigen::Vector3d p = 2 * Eigen::Vector3d::Random();
    const Eigen::Vector3d bary = pc::closestPointOnTriangle(p, a, b, c);
    EXPECT_GE(bary.minCoeff(), -1e-12);
    EXPECT_NEAR(bary.sum(), 1.0, 1e-12);
    const double exact = (p - (bary(0) * a + bary(1) * b + bary(2) * c)).norm();
    double sampled = 1e9;
    const int n = 60;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double u = double(i) / n, v = double(j) / n;
        sampled = std::min(sampled, (p - ((1 - u - v) * a + u * b + v * c)).norm());
      }
    EXPECT_LE(exact, sampled + 1e-12);
    EXPECT_GE(exact,
              sampled - 0.06);  // every point of the triangle is within 1/60 of its longest edge (< 3.5) of the grid
  }
  // Each region: interior, edge, corner.
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(pc::closestPointOnTriangle({0.25, 0.25, 3}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.25, 0.25)));
  EXPECT_TRUE(pc::closestPointOnTriangle({0.5, -1, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
  EXPECT_TRUE(pc::closestPointOnTriangle({2, 2, 0}, a, b, c).isApprox(Eigen::Vector3d(0, 0.5, 0.5)));
  EXPECT_TRUE(pc::closestPointOnTriangle({-1, -1, 1}, a, b, c).isApprox(Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE(pc::closestPointOnTriangle({3, -0.5, 0}, a, b, c).isApprox(Eigen::Vector3d(0, 1, 0)));
}
