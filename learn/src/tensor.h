#pragma once

// Eigen <-> LibTorch conversions, in one place (learn/-internal).

#include <torch/torch.h>

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "pixelcloth/core/npy.h"

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

/// A copy of the tensor's values as an array of a tensor file (core/tensor_file.h). Throws `InputError` naming `name`
/// for a scalar type the file cannot hold (float32, float64, int32, int64 and uint8 it can).
core::NpyArray arrayOfTensor(const torch::Tensor& tensor, const std::string& name);

/// Copies `array` (named `name` in the tensor file `path`) into `tensor`. Throws `InputError` naming both when its
/// dtype or shape differs from the tensor's (the weights of another network than `what`) or a value is not finite.
void copyArrayInto(torch::Tensor& tensor, const core::NpyArray& array, const std::string& name,
                   const std::filesystem::path& path, const std::string& what);

}  // namespace pixelcloth::learn
