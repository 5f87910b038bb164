// Principal components of rows of data, three ways: the exact SVD (small problems, the reference), the Gram matrix
// through sgemm and LAPACK's symmetric eigensolver, and a randomised range finder. The last two are what a 16K x 9K
// training split needs (the PCA filter, DESIGN.md "Stitching"); bench's stitch.pca_fit lines time both.
#include <torch/torch.h>

#include <algorithm>
#include <cstdlib>
#include <thread>

#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/learn/cpu.h"
#include "pixelcloth/learn/model.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace {

const core::EnumNames<PcaMethod, 3> kMethods{
    "PCA method", {{{PcaMethod::Svd, "svd"}, {PcaMethod::Gram, "gram"}, {PcaMethod::Randomized, "randomized"}}}};

/// Orthonormal columns spanning those of `a` (reduced QR).
torch::Tensor orthonormalColumns(const torch::Tensor& a) { return std::get<0>(torch::linalg::qr(a, "reduced")); }

/// The eigenvectors of the symmetric `gram` (float32, p x p) with the `k` largest eigenvalues, solved in double
/// precision: (eigenvalues descending {k}, eigenvectors as columns {p, k}), float32.
std::pair<torch::Tensor, torch::Tensor> topEigen(const torch::Tensor& gram, std::int64_t k) {
  const auto [values, vectors] = torch::linalg::eigh(gram.to(torch::kFloat64), "L");
  const std::int64_t p = gram.size(0);
  const torch::Tensor order = torch::arange(p - 1, p - 1 - k, -1, torch::kLong);
  return {values.index_select(0, order).clamp_min(0).to(torch::kFloat32),
          vectors.index_select(1, order).to(torch::kFloat32)};
}

/// Rows `components` (k x m) and variances `variance` (k) from the centred data's right singular vectors.
PcaBasis finish(const torch::Tensor& mean, torch::Tensor components, const torch::Tensor& variance) {
  // Sign: each component's largest entry in magnitude positive, so that every method gives the same vectors.
  const torch::Tensor peak = components.abs().argmax(1, /*keepdim=*/true);
  const torch::Tensor sign = components.gather(1, peak).sign();
  components = components * torch::where(sign == 0, torch::ones_like(sign), sign);
  PcaBasis basis;
  basis.mean = toEigen(mean.reshape({1, -1}).to(torch::kFloat32)).transpose();
  basis.components = toEigen(components.to(torch::kFloat32).contiguous());
  basis.variance = toEigen(variance.reshape({1, -1}).to(torch::kFloat32)).transpose();
  return basis;
}

}  // namespace

const char* pcaMethodName(PcaMethod method) { return kMethods.name(method); }
PcaMethod pcaMethodFromName(const std::string& name, const std::string& context) {
  return kMethods.fromName(name, context);
}

Eigen::MatrixXf PcaBasis::project(const Eigen::MatrixXf& data) const {
  PIXELCLOTH_CHECK(data.cols() == mean.size(), "pca: " << data.cols() << " values per row, expected " << mean.size());
  return (data.rowwise() - mean.transpose()) * components.transpose();
}

Eigen::MatrixXf PcaBasis::reconstruct(const Eigen::MatrixXf& coefficients) const {
  PIXELCLOTH_CHECK(coefficients.cols() == components.rows(),
                   "pca: " << coefficients.cols() << " coefficients per row, expected " << components.rows());
  return (coefficients * components).rowwise() + mean.transpose();
}

PcaBasis fitPca(const Eigen::MatrixXf& data, int components, PcaMethod method, std::uint64_t seed) {
  const std::int64_t n = data.rows(), m = data.cols();
  PIXELCLOTH_CHECK(n >= 1 && m >= 1 && data.allFinite(), "pca: " << n << " x " << m << " data, expected finite rows");
  PIXELCLOTH_CHECK(components >= 1 && components <= std::min(n, m), "pca: " << components << " components of " << n
                                                                            << " x " << m << " data, expected 1 to "
                                                                            << std::min(n, m));
  torch::NoGradGuard noGrad;
  const ThreadScope cores(0);
  const std::int64_t k = components;
  const double dof = static_cast<double>(std::max<std::int64_t>(n - 1, 1));
  torch::Tensor x = toTensor(data);
  const torch::Tensor mean = x.mean(0);
  x -= mean;
  switch (method) {
    case PcaMethod::Svd: {
      const torch::Tensor x64 = x.to(torch::kFloat64);
      const auto [u, s, vh] = torch::linalg::svd(x64, /*full_matrices=*/false, c10::nullopt);
      return finish(mean, vh.slice(0, 0, k), s.slice(0, 0, k).pow(2) / dof);
    }
    case PcaMethod::Gram: {
      if (m <= n) {  // X^T X: m x m, its eigenvectors are the components
        const auto [values, vectors] = topEigen(torch::mm(x.t(), x), k);
        return finish(mean, vectors.t(), values / dof);
      }
      // X X^T: n x n; components = X^T u / sigma. Directions of (nearly) zero variance come out of that as noise of
      // any length: the QR makes them unit and orthogonal to the rest, and leaves the others as they are (up to sign).
      const auto [values, u] = topEigen(torch::mm(x, x.t()), k);
      const torch::Tensor sigma = values.sqrt();
      const torch::Tensor v = torch::mm(x.t(), u) / torch::where(sigma > 0, sigma, torch::ones_like(sigma));
      return finish(mean, orthonormalColumns(v).t(), values / dof);
    }
    case PcaMethod::Randomized: {
      // The range finder on the values' side (Halko et al. 2011, section 4 with one power iteration): Z spans
      // (X^T X) Omega, l = k plus oversampling columns, orthonormalised once (a QR of #values rows, the cheaper side).
      // The SVD of X Z then gives the components as Z W: three products the size of X, one QR, one small eigensolve.
      const std::int64_t l = std::min<std::int64_t>(std::min(n, m), k + std::max<std::int64_t>(16, k / 8));
      torch::Generator generator = at::detail::createCPUGenerator(seed);
      const torch::Tensor omega = torch::randn({m, l}, generator, torch::dtype(torch::kFloat32));
      const torch::Tensor z = orthonormalColumns(torch::mm(x.t(), torch::mm(x, omega)));
      const torch::Tensor c = torch::mm(x, z);  // n x l
      const auto [values, w] = topEigen(torch::mm(c.t(), c), k);
      return finish(mean, torch::mm(z, w).t(), values / dof);  // orthonormal columns times an orthogonal W
    }
  }
  PIXELCLOTH_ASSERT(false, "unknown PCA method");
  return {};
}

}  // namespace pixelcloth::learn
