#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

/// The NumPy dtype string of an element type: float "<f4", double "<f8", int32 "<i4", int64 "<i8", uint8 "|u1".
template <typename T>
constexpr const char* npyDtype();
template <>
constexpr const char* npyDtype<float>() {
  return "<f4";
}
template <>
constexpr const char* npyDtype<double>() {
  return "<f8";
}
template <>
constexpr const char* npyDtype<std::int32_t>() {
  return "<i4";
}
template <>
constexpr const char* npyDtype<std::int64_t>() {
  return "<i8";
}
template <>
constexpr const char* npyDtype<std::uint8_t>() {
  return "|u1";
}

/// An n-dimensional array as a NumPy .npy file holds it: C order (last index fastest), little endian.
struct NpyArray {
  std::string dtype;                 ///< "<f4", "<f8", "<i4", "<i8" or "|u1"
  std::vector<std::int64_t> shape;   ///< one entry per dimension; empty for a 0-d (scalar) array
  std::vector<unsigned char> bytes;  ///< size() * itemSize() bytes, C order, little endian
  std::string source;                ///< the file it was read from, for messages; empty when built in memory

  /// Number of elements: the product of `shape` (1 for a scalar).
  std::int64_t size() const;
  /// Bytes per element of `dtype` (throws `InputError` for an unsupported dtype).
  int itemSize() const;
  /// The elements as T; throws `InputError` when T does not match `dtype` ("x.npy: dtype <f8, expected <f4").
  template <typename T>
  const T* data() const {
    checkDtype(npyDtype<T>());
    return reinterpret_cast<const T*>(bytes.data());
  }
  /// Builds an array of `values` (C order) with `shape`; throws `InputError` when the counts disagree.
  template <typename T>
  static NpyArray from(const std::vector<T>& values, std::vector<std::int64_t> shape) {
    NpyArray array{npyDtype<T>(), std::move(shape), {}, {}};
    PIXELCLOTH_CHECK(array.size() == static_cast<std::int64_t>(values.size()),
                     "npy array: " << values.size() << " values for shape " << array.shapeString() << " ("
                                   << array.size() << " elements)");
    const auto* begin = reinterpret_cast<const unsigned char*>(values.data());
    array.bytes.assign(begin, begin + values.size() * sizeof(T));
    return array;
  }
  /// The shape as Python writes it: "(3, 4)", "(5,)", "()".
  std::string shapeString() const;
  /// Throws `InputError` ("<source>: dtype <f8, expected <f4") unless `dtype == expected`.
  void checkDtype(const std::string& expected) const;
};

/// A shape as Python writes it: "(3, 4)", "(5,)", "()".
std::string npyShapeString(const std::vector<std::int64_t>& shape);

/// What the header of a .npy file says, without reading its data: for arrays streamed row by row (datasets of a GB).
struct NpyHeader {
  std::string dtype;                ///< "<f4", "<f8", "<i4", "<i8" or "|u1"
  std::vector<std::int64_t> shape;  ///< one entry per dimension
  std::int64_t itemSize = 0;        ///< bytes per element
  std::int64_t dataOffset = 0;      ///< where the data starts in the file (bytes)
  std::int64_t elements() const;    ///< product of `shape`
  std::string shapeString() const { return npyShapeString(shape); }
};

/// Reads and checks the header of a .npy file, with the messages of readNpy: magic, version 1.0-3.0, the header dict,
/// C order, little endian and a supported dtype, and a data length that is exactly what the shape needs.
NpyHeader readNpyHeader(const std::filesystem::path& path);

/// The bytes writeNpy puts before the data of an array of `dtype` and `shape`: magic, version (1.0, or 2.0 for a
/// header over 64 KiB) and the header dict padded so that the data starts on a 64-byte boundary, as numpy does.
std::string npyPreamble(const std::string& dtype, const std::vector<std::int64_t>& shape);

/// Reads a .npy file, format version 1.0, 2.0 or 3.0. Throws `InputError` naming the file for a missing file, bad
/// magic, a malformed header, fortran_order True, a big-endian or unsupported dtype, and data shorter or longer than
/// the shape needs.
NpyArray readNpy(const std::filesystem::path& path);

/// Writes `array` as a .npy file (version 1.0, or 2.0 when the header needs more than 65535 bytes), atomically.
void writeNpy(const std::filesystem::path& path, const NpyArray& array);

/// Writes `values` (C order) with `shape`, e.g. `writeNpy(p, offsets, {samples, vertices, 3})`.
template <typename T>
void writeNpy(const std::filesystem::path& path, const std::vector<T>& values, std::vector<std::int64_t> shape) {
  writeNpy(path, NpyArray::from(values, std::move(shape)));
}

/// Writes a matrix as a 2-D array of shape (rows, cols) with dtype <f4, <f8 or <i4 (element order converted to C).
/// Pass a matrix, not an expression (`Zero(...)` is ambiguous between the overloads: add `.eval()`).
void writeNpy(const std::filesystem::path& path, const Eigen::MatrixXf& matrix);
void writeNpy(const std::filesystem::path& path, const Eigen::MatrixXd& matrix);
void writeNpy(const std::filesystem::path& path, const Eigen::MatrixXi& matrix);

/// Reads a 2-D array as a matrix. The dtype must be exactly float32 <f4 (F), float64 <f8 (D) or int32 <i4 (I): no
/// silent conversion. `rowsExpected` / `colsExpected` (-1: any) are checked: "weights.npy: shape (100, 12), expected
/// (15204, 12)".
Eigen::MatrixXf readNpyMatrixF(const std::filesystem::path& path, std::int64_t rowsExpected = -1,
                               std::int64_t colsExpected = -1);
Eigen::MatrixXd readNpyMatrixD(const std::filesystem::path& path, std::int64_t rowsExpected = -1,
                               std::int64_t colsExpected = -1);
Eigen::MatrixXi readNpyMatrixI(const std::filesystem::path& path, std::int64_t rowsExpected = -1,
                               std::int64_t colsExpected = -1);

}  // namespace pixelcloth::core
