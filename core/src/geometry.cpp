#include "pixelcloth/core/geometry.h"

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

namespace {
/// Twice the area of a triangle given by two edge vectors (2 or 3 components).
double doubleArea(const Eigen::VectorXd& e1, const Eigen::VectorXd& e2) {
  if (e1.size() == 2) return std::abs(e1.x() * e2.y() - e1.y() * e2.x());
  return Eigen::Vector3d(e1).cross(Eigen::Vector3d(e2)).norm();
}

void checkDimensions(const Eigen::Ref<const Eigen::MatrixXd>& P, const char* what) {
  PIXELCLOTH_CHECK(P.cols() == 2 || P.cols() == 3,
                   what << ": positions have " << P.cols() << " columns, expected 2 or 3");
}
}  // namespace

Eigen::VectorXd triangleAreas(const Eigen::Ref<const Eigen::MatrixXd>& V, const Eigen::MatrixX3i& F) {
  checkDimensions(V, "triangle areas");
  Eigen::VectorXd area(F.rows());
  for (int f = 0; f < F.rows(); ++f)
    area[f] = 0.5 * doubleArea(V.row(F(f, 1)) - V.row(F(f, 0)), V.row(F(f, 2)) - V.row(F(f, 0)));
  return area;
}

Eigen::VectorXd areaRatios(const Eigen::MatrixX3d& positions, const Mesh& pattern) {
  PIXELCLOTH_CHECK(positions.rows() == pattern.numVertices() && pattern.hasUV(),
                   "area ratios: " << positions.rows() << " positions for a mesh of " << pattern.numVertices()
                                   << " vertices" << (pattern.hasUV() ? "" : " without UVs"));
  const Eigen::VectorXd worn = triangleAreas(positions, pattern.F), flat = triangleAreas(pattern.UV, pattern.FUV);
  Eigen::VectorXd ratio(pattern.numFaces());
  for (int f = 0; f < pattern.numFaces(); ++f) ratio[f] = flat[f] > 0 ? worn[f] / flat[f] : 1.0;
  return ratio;
}

Eigen::SparseMatrix<double> cotangentLaplacian(const Eigen::Ref<const Eigen::MatrixXd>& P, const Eigen::MatrixX3i& FP,
                                               const Eigen::MatrixX3i& F, int n) {
  checkDimensions(P, "cotangent Laplacian");
  PIXELCLOTH_CHECK(FP.rows() == F.rows(),
                   "cotangent Laplacian: " << FP.rows() << " corner rows for " << F.rows() << " triangles");
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(12 * F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, (k + 1) % 3), j = F(f, (k + 2) % 3);
      const Eigen::VectorXd e1 = (P.row(FP(f, (k + 1) % 3)) - P.row(FP(f, k))).transpose(),
                            e2 = (P.row(FP(f, (k + 2) % 3)) - P.row(FP(f, k))).transpose();
      const double sine = doubleArea(e1, e2);
      if (!(sine > 1e-20)) continue;
      const double w = 0.5 * e1.dot(e2) / sine;
      triplets.emplace_back(i, j, w);
      triplets.emplace_back(j, i, w);
      triplets.emplace_back(i, i, -w);
      triplets.emplace_back(j, j, -w);
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

Eigen::SparseMatrix<double> cotangentLaplacian(const Eigen::Ref<const Eigen::MatrixXd>& V, const Eigen::MatrixX3i& F) {
  return cotangentLaplacian(V, F, F, static_cast<int>(V.rows()));
}

Eigen::VectorXd lumpedMass(const Eigen::Ref<const Eigen::MatrixXd>& V, const Eigen::MatrixX3i& F) {
  const Eigen::VectorXd area = triangleAreas(V, F);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(V.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) mass[F(f, k)] += area[f] / 3.0;
  return mass;
}

}  // namespace pixelcloth::core
