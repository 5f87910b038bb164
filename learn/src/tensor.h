#pragma once

// Eigen <-> LibTorch conversions, in one place (learn/-internal).

#include <torch/torch.h>

#include <Eigen/Core>

namespace pixelcloth::learn {

/// A float tensor (rows x cols, row-major) holding a copy of `m`.
inline torch::Tensor toTensor(const Eigen::MatrixXf& m) {
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = m;
  return torch::from_blob(const_cast<float*>(rows.data()), {rows.rows(), rows.cols()}, torch::kFloat32).clone();
}

/// A float matrix of a tensor, its first dimension the rows and the rest flattened (C order).
inline Eigen::MatrixXf toEigen(const torch::Tensor& t) {
  const torch::Tensor c = t.to(torch::kCPU).contiguous().reshape({t.size(0), -1});
  Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> rows(c.data_ptr<float>(),
                                                                                               c.size(0), c.size(1));
  return rows;
}

}  // namespace pixelcloth::learn
