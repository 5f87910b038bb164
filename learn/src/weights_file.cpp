#include "pixelcloth/learn/weights_file.h"

#include <torch/torch.h>

#include <cmath>
#include <cstring>
#include <set>

#include "pixelcloth/core/error.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace fs = std::filesystem;

namespace {

const char* dtypeOf(torch::ScalarType type) {
  switch (type) {
    case torch::kFloat32: return "<f4";
    case torch::kFloat64: return "<f8";
    case torch::kInt32: return "<i4";
    case torch::kInt64: return "<i8";
    case torch::kUInt8: return "|u1";
    default: return nullptr;
  }
}

}  // namespace

core::NpyArray arrayOfTensor(const torch::Tensor& tensor, const std::string& name) {
  const torch::Tensor t = tensor.detach().to(torch::kCPU).contiguous();
  const char* dtype = dtypeOf(t.scalar_type());
  PIXELCLOTH_CHECK(dtype, name << ": a tensor of type " << t.scalar_type() << ", which tensor files do not hold");
  core::NpyArray array{dtype, t.sizes().vec(), {}, {}};
  const auto* begin = static_cast<const unsigned char*>(t.data_ptr());
  array.bytes.assign(begin, begin + t.numel() * t.element_size());
  return array;
}

namespace {

// Where the first value that is not finite is, or -1.
template <typename T>
std::int64_t firstNonFinite(const core::NpyArray& array) {
  const T* values = array.data<T>();
  for (std::int64_t i = 0; i < array.size(); ++i)
    if (!std::isfinite(values[i])) return i;
  return -1;
}

}  // namespace

void copyArrayInto(torch::Tensor& tensor, const core::NpyArray& array, const std::string& name, const fs::path& path,
              const std::string& what) {
  const char* dtype = dtypeOf(tensor.scalar_type());
  PIXELCLOTH_CHECK(dtype && array.dtype == dtype && array.shape == tensor.sizes().vec(),
                   path.string() << ": array '" << name << "' is " << array.dtype << " " << array.shapeString()
                                 << ", " << what << " has " << (dtype ? dtype : "?") << " "
                                 << core::npyShapeString(tensor.sizes().vec())
                                 << " there (the weights of another architecture or width)");
  const std::int64_t bad = array.dtype == "<f4"   ? firstNonFinite<float>(array)
                           : array.dtype == "<f8" ? firstNonFinite<double>(array)
                                                  : -1;
  PIXELCLOTH_CHECK(bad < 0, path.string() << ": array '" << name << "' holds a value that is not finite (element "
                                          << bad + 1 << ", counting from 1)");
  torch::NoGradGuard noGrad;
  const torch::Tensor source =
      torch::from_blob(const_cast<unsigned char*>(array.bytes.data()), tensor.sizes(), tensor.scalar_type());
  tensor.copy_(source);
}

void appendModuleArrays(const torch::nn::Module& module, core::TensorFile& file, const std::string& prefix) {
  for (const auto& item : module.named_parameters(/*recurse=*/true))
    file.arrays.emplace_back(prefix + item.key(), arrayOfTensor(item.value(), item.key()));
  for (const auto& item : module.named_buffers(/*recurse=*/true))
    file.arrays.emplace_back(prefix + item.key(), arrayOfTensor(item.value(), item.key()));
}

void loadModuleArrays(torch::nn::Module& module, const core::TensorFile& file, const fs::path& path,
                      const std::string& what, const std::string& prefix) {
  std::set<std::string> wanted;
  auto load = [&](const std::string& key, torch::Tensor tensor) {
    const std::string name = prefix + key;
    wanted.insert(name);
    const core::NpyArray* array = file.find(name);
    PIXELCLOTH_CHECK(array, path.string() << ": has no array '" << name << "', which " << what
                                          << " needs (the weights of another architecture)");
    copyArrayInto(tensor, *array, name, path, what);
  };
  for (auto& item : module.named_parameters(/*recurse=*/true)) load(item.key(), item.value());
  for (auto& item : module.named_buffers(/*recurse=*/true)) load(item.key(), item.value());
  if (!prefix.empty()) return;
  for (const auto& [name, array] : file.arrays)
    PIXELCLOTH_CHECK(wanted.count(name), path.string() << ": holds array '" << name << "', which " << what
                                                       << " has not (the weights of another architecture)");
}

void saveModuleWeights(const torch::nn::Module& module, const fs::path& path, const nlohmann::json& meta) {
  core::TensorFile file;
  file.kind = "weights";
  file.meta = meta;
  appendModuleArrays(module, file);
  core::writeTensorFile(path, file);
}

void loadModuleWeights(torch::nn::Module& module, const fs::path& path, const std::string& what) {
  loadModuleArrays(module, core::readTensorFile(path, "weights"), path, what);
}

}  // namespace pixelcloth::learn
