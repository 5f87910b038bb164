// The geometry every stage shares, checked directly: the cotangent Laplacian and lumped mass, and the spatial index
// over a mesh (closest point, segment test, inside test, smooth normals).
#include "pixelcloth/core/geometry.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh_index.h"
#include "pixelcloth/core/self_intersection.h"

namespace pc = pixelcloth::core;

namespace {

/// An n x n grid of unit-spaced vertices in the plane z = 0, two triangles per cell.
void grid(int n, Eigen::MatrixXd& V, Eigen::MatrixX3i& F) {
  V.resize(n * n, 3);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) V.row(y * n + x) << x, y, 0;
  F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x, b = a + 1, c = a + n + 1, d = a + n;
      F.row(f++) << a, b, c;
      F.row(f++) << a, c, d;
    }
}

/// The unit cube [0, 1]^3 as 12 outward-facing triangles.
void cube(Eigen::MatrixX3d& V, Eigen::MatrixX3i& F) {
  V.resize(8, 3);
  for (int i = 0; i < 8; ++i) V.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  F.resize(12, 3);
  F << 0, 2, 1, 1, 2, 3,  // z = 0, normal -z
      4, 5, 6, 5, 7, 6,   // z = 1, +z
      0, 1, 4, 1, 5, 4,   // y = 0, -y
      2, 6, 3, 3, 6, 7,   // y = 1, +y
      0, 4, 2, 2, 4, 6,   // x = 0, -x
      1, 3, 5, 3, 7, 5;   // x = 1, +x
}

}  // namespace

TEST(CotangentLaplacian, TheUnitSquaresWeightsAreHalfCotangentsOfTheOppositeAngles) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::MatrixX3i F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  const Eigen::MatrixXd L = Eigen::MatrixXd(pc::cotangentLaplacian(V, F));
  EXPECT_NEAR(L(0, 1), 0.5, 1e-12);  // opposite a 45 degree corner: cot = 1
  EXPECT_NEAR(L(0, 2), 0.0, 1e-12);  // the diagonal, opposite two right angles
  EXPECT_NEAR(L(1, 3), 0.0, 1e-12);  // no edge
  EXPECT_NEAR(L(0, 0), -1.0, 1e-12);
  EXPECT_TRUE(L.isApprox(L.transpose()));
}

TEST(CotangentLaplacian, RowsSumToZeroAndLinearFunctionsAreHarmonicInside) {
  Eigen::MatrixXd V;
  Eigen::MatrixX3i F;
  grid(6, V, F);
  // A little shear keeps the mesh planar but makes the angles unequal.
  V.col(0) += 0.3 * V.col(1);
  const Eigen::SparseMatrix<double> L = pc::cotangentLaplacian(V, F);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(V.rows());
  EXPECT_LT((L * ones).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::VectorXd linear = 2 * V.col(0) - 3 * V.col(1) + Eigen::VectorXd::Constant(V.rows(), 0.5);
  const Eigen::VectorXd Lx = L * linear;
  for (int y = 1; y < 5; ++y)
    for (int x = 1; x < 5; ++x) EXPECT_NEAR(Lx(y * 6 + x), 0.0, 1e-10) << x << ", " << y;
  // Negative semi-definite: x^T L x <= 0.
  const Eigen::VectorXd random = Eigen::VectorXd::Random(V.rows());
  EXPECT_LE(random.dot(L * random), 1e-12);
}

TEST(CotangentLaplacian, APatternWithItsOwnCornersAndADegenerateTriangle) {
  Eigen::MatrixXd V;
  Eigen::MatrixX3i F;
  grid(3, V, F);
  // The same triangles through FP = F give the mesh's own Laplacian.
  const Eigen::MatrixXd own = Eigen::MatrixXd(pc::cotangentLaplacian(V, F));
  EXPECT_TRUE(Eigen::MatrixXd(pc::cotangentLaplacian(V, F, F, static_cast<int>(V.rows()))).isApprox(own));
  // 2D positions give the same as the plane z = 0.
  EXPECT_TRUE(Eigen::MatrixXd(pc::cotangentLaplacian(V.leftCols(2), F)).isApprox(own));
  // A triangle with all corners at one point adds nothing.
  Eigen::MatrixX3i withDegenerate(F.rows() + 1, 3);
  withDegenerate << F, 0, 0, 0;
  EXPECT_TRUE(Eigen::MatrixXd(pc::cotangentLaplacian(V, withDegenerate)).isApprox(own));
}

TEST(LumpedMass, SumsToTheAreaAndGivesEachCornerAThird) {
  Eigen::MatrixXd V;
  Eigen::MatrixX3i F;
  grid(4, V, F);
  V *= 0.5;
  const Eigen::VectorXd mass = pc::lumpedMass(V, F);
  EXPECT_NEAR(mass.sum(), 1.5 * 1.5, 1e-12);
  EXPECT_NEAR(mass(0), 2 * 0.125 / 3, 1e-12);  // the corner a cell's diagonal starts from touches both its triangles
  EXPECT_NEAR(mass(3), 0.125 / 3, 1e-12);
}

TEST(SelfIntersections, AFaceThroughAnotherIsFoundNeighboursAreNot) {
  Eigen::MatrixX3d V(7, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,       // a square of two faces
      0.7, 0.3, -1, 0.75, 0.3, 1, 0.7, 0.35, 1;  // a triangle through the first face
  Eigen::MatrixX3i F(3, 3);
  F << 0, 1, 2, 0, 2, 3, 4, 5, 6;
  EXPECT_TRUE(pc::selfIntersections(V, F.topRows(2)).empty());  // two faces sharing an edge
  EXPECT_EQ(pc::selfIntersections(V, F), (std::vector<std::pair<int, int>>{{0, 2}}));
  V.row(4) << 0.7, 0.3, 0.5;  // lifted clear of the square
  EXPECT_TRUE(pc::selfIntersections(V, F).empty());
  // Three faces on one edge: not a manifold mesh.
  Eigen::MatrixX3i fan(3, 3);
  fan << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  EXPECT_THROW(pc::selfIntersections(V, fan), pc::InputError);
}

TEST(MeshIndex, ClosestPointsOnTheUnitCube) {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  cube(V, F);
  const pc::MeshIndex index(V, F);
  const pc::MeshHit hit = index.closest(Eigen::Vector3d(2, 0.4, 0.7));
  EXPECT_NEAR(hit.distance, 1.0, 1e-12);
  EXPECT_TRUE(hit.point.isApprox(Eigen::Vector3d(1, 0.4, 0.7), 1e-12));
  ASSERT_GE(hit.face, 0);
  // The barycentric coordinates reproduce the point on the face found.
  Eigen::Vector3d fromBarycentric = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) fromBarycentric += hit.barycentric(k) * V.row(F(hit.face, k)).transpose();
  EXPECT_TRUE(fromBarycentric.isApprox(hit.point, 1e-12));
  EXPECT_NEAR(hit.barycentric.sum(), 1.0, 1e-12);
  // Beyond a corner, the corner; from inside, the nearest face.
  EXPECT_TRUE(index.closest(Eigen::Vector3d(-1, -1, -1)).point.isApprox(Eigen::Vector3d(0, 0, 0), 1e-12));
  EXPECT_NEAR(index.closest(Eigen::Vector3d(0.5, 0.5, 0.9)).distance, 0.1, 1e-12);
  // Started from an earlier answer nearby, the same answer.
  const pc::MeshHit moved = index.closest(Eigen::Vector3d(2.01, 0.41, 0.69), hit);
  EXPECT_TRUE(moved.point.isApprox(index.closest(Eigen::Vector3d(2.01, 0.41, 0.69)).point, 1e-12));
}

TEST(MeshIndex, InsideSegmentsAndNormalsOfTheUnitCube) {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  cube(V, F);
  const pc::MeshIndex index(V, F);
  EXPECT_TRUE(index.inside(Eigen::Vector3d(0.5, 0.5, 0.5)));
  EXPECT_TRUE(index.inside(Eigen::Vector3d(0.99, 0.01, 0.5)));
  EXPECT_FALSE(index.inside(Eigen::Vector3d(1.01, 0.5, 0.5)));
  EXPECT_FALSE(index.inside(Eigen::Vector3d(-3, 7, 0.5)));
  Eigen::MatrixX3d points(3, 3);
  points << 0.5, 0.5, 0.5, 2, 2, 2, 0.2, 0.8, 0.1;
  EXPECT_EQ(index.inside(points), (std::vector<bool>{true, false, true}));
  EXPECT_EQ(pc::insideClosedMesh(V, F, points), (std::vector<bool>{true, false, true}));
  EXPECT_TRUE(index.intersects(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(0.5, 0.5, 3)));
  EXPECT_FALSE(index.intersects(Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(2, 3, 3)));
  // At the middle of the +x face, the smooth normal points out along +x, and is a unit vector.
  const pc::MeshHit hit = index.closest(Eigen::Vector3d(3, 0.5, 0.5));
  const Eigen::Vector3d normal = index.smoothNormal(hit.face, hit.barycentric);
  EXPECT_NEAR(normal.norm(), 1.0, 1e-12);
  EXPECT_GT(normal.x(), 0.5);
}

TEST(MeshIndex, RayCrossingsCountEverySheetOfAMeshThatPassesThroughItself) {
  // Two unit cubes in one mesh, the second shifted half a cube along x: a point in the second only (x in (1, 1.5))
  // is nearer the first's skin, which it is outside of, yet every ray from it crosses the mesh an odd number of times.
  Eigen::MatrixX3d V, V2;
  Eigen::MatrixX3i F, F2;
  cube(V, F);
  cube(V2, F2);
  Eigen::MatrixX3d both(16, 3);
  both << V, V2.rowwise() + Eigen::RowVector3d(0.5, 0, 0);
  Eigen::MatrixX3i faces(2 * F.rows(), 3);
  faces << F, F2.array() + 8;
  const pc::MeshIndex index(both, faces);
  const Eigen::Vector3d enclosed(1.05, 0.37, 0.61);
  EXPECT_FALSE(index.inside(enclosed));  // the nearest sheet's test sees only the first cube's +x face
  for (const Eigen::Vector3d direction :
       {Eigen::Vector3d(0.36, 0.48, 0.8), Eigen::Vector3d(-1, 0.1, 0.2), Eigen::Vector3d(0.1, -0.3, -1)})
    EXPECT_EQ(index.crossings(enclosed, direction) % 2, 1) << direction.transpose();
  // In both cubes: two sheets around it, an even count; outside both: even too, 0 away from them.
  EXPECT_EQ(index.crossings(Eigen::Vector3d(0.8, 0.37, 0.61), Eigen::Vector3d(1, 0.1, 0.2)), 2);
  EXPECT_EQ(index.crossings(Eigen::Vector3d(3, 0.37, 0.61), Eigen::Vector3d(1, 0.1, 0.2)), 0);
  EXPECT_EQ(index.crossings(Eigen::Vector3d(-1, 0.37, 0.61), Eigen::Vector3d(1, 0.1, 0.2)), 4);
}

TEST(MeshIndex, FacesOutsideTheVerticesAreRefused) {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  cube(V, F);
  F(3, 1) = 8;
  EXPECT_THROW(pc::MeshIndex(V, F), std::exception);
}
