#include "target.h"

#include <algorithm>
#include <set>

#include "pixelcloth/core/error.h"
#include "losses.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace {

class WholeImageTarget : public Target {
 public:
  explicit WholeImageTarget(const garment::Garment& garment) : imager_(garment) {
    const int V = garment.mesh.numVertices(), L = static_cast<int>(imager_.layouts().size());
    const patches::ClothImage blank = imager_.rasterize(Eigen::MatrixXf::Zero(V, 3));
    shape_ = {3 * L, blank.height, blank.width};
    mask_ = torch::zeros({3 * L, blank.height, blank.width});
    for (int l = 0; l < L; ++l)
      for (int c = 0; c < 3; ++c) mask_[3 * l + c].copy_(toTensor(blank.layers[l].mask).gt(0.5));
    vertices_.resize(V);
    for (int v = 0; v < V; ++v) vertices_[v] = v;
    // A seam vertex is in two layouts: each layout's sample counts half, as ClothImager::sample averages them.
    std::vector<float> layoutsOf(V, 0.0f);
    for (int l = 0; l < L; ++l)
      for (int v : imager_.sampler(l).vertices) layoutsOf[v] += 1;
    std::vector<float> scale(V);
    for (int v = 0; v < V; ++v) scale[v] = layoutsOf[v] > 0 ? 1.0f / layoutsOf[v] : 0.0f;
    for (int l = 0; l < L; ++l) samplers_.push_back(sparseRows(imager_.sampler(l).matrix, vertices_, scale));
    std::vector<int> faces(garment.mesh.F.rows());
    for (size_t f = 0; f < faces.size(); ++f) faces[f] = static_cast<int>(f);
    setMesh(garment, faces);
  }

  torch::Tensor encode(const Eigen::MatrixXf& values) const override {
    const patches::ClothImage image = imager_.rasterize(values);
    std::vector<torch::Tensor> channels;
    for (const patches::ClothLayer& layer : image.layers)
      for (const Eigen::MatrixXf* c : {&layer.du, &layer.dv, &layer.dn}) channels.push_back(toTensor(*c));
    return torch::stack(channels);
  }

  void to(const torch::Device& device) override {
    Target::to(device);
    for (torch::Tensor& s : samplers_) s = s.to(device);
  }

  torch::Tensor decode(const torch::Tensor& output) const override {
    torch::Tensor sum;
    for (size_t l = 0; l < samplers_.size(); ++l) {
      const torch::Tensor part = sampleImage(samplers_[l], output.slice(1, 3 * l, 3 * l + 3));
      sum = l == 0 ? part : sum + part;
    }
    return sum;
  }

 private:
  patches::ClothImager imager_;
  std::vector<torch::Tensor> samplers_;
};

class PatchCropTarget : public Target {
 public:
  PatchCropTarget(const garment::Garment& garment, const patches::Patch& patch) {
    patches::EnlargedCrop crop = patches::enlargedCrop(garment, patch);
    raster_ = std::move(crop.raster);
    vertices_ = crop.sample.vertices;
    shape_ = {3, crop.frame.height, crop.frame.width};
    mask_ = toTensor(raster_.maskImage()).gt(0.5).to(torch::kFloat32).unsqueeze(0);
    sampler_ = sparseRows(crop.sample.matrix, vertices_);
    setMesh(garment, crop.faces);
  }

  torch::Tensor encode(const Eigen::MatrixXf& values) const override {
    const Eigen::MatrixXf pixels = raster_.apply(values);  // (H W) x 3
    return toTensor(pixels).t().reshape({3, shape_[1], shape_[2]}).contiguous();
  }

  torch::Tensor decode(const torch::Tensor& output) const override { return sampleImage(sampler_, output); }

  void to(const torch::Device& device) override {
    Target::to(device);
    sampler_ = sampler_.to(device);
  }

 private:
  patches::RasterOperator raster_;
  torch::Tensor sampler_;
};

class VertexTarget : public Target {
 public:
  explicit VertexTarget(const garment::Garment& garment) {
    const int V = garment.mesh.numVertices();
    shape_ = {3 * V};
    mask_ = torch::ones({3 * V});
    vertices_.resize(V);
    for (int v = 0; v < V; ++v) vertices_[v] = v;
    std::vector<int> faces(garment.mesh.F.rows());
    for (size_t f = 0; f < faces.size(); ++f) faces[f] = static_cast<int>(f);
    setMesh(garment, faces);
  }

  torch::Tensor encode(const Eigen::MatrixXf& values) const override {
    return toTensor(values).reshape({-1});  // row-major: vertex by vertex
  }

  torch::Tensor decode(const torch::Tensor& output) const override {
    return output.reshape({output.size(0), -1, 3});
  }
};

}  // namespace

void Target::to(const torch::Device& device) {
  mask_ = mask_.to(device);
  faces_ = faces_.to(device);
  edges_ = edges_.to(device);
}

void Target::setMesh(const garment::Garment& garment, const std::vector<int>& garmentFaces) {
  std::vector<int> local(garment.mesh.numVertices(), -1);
  for (size_t i = 0; i < vertices_.size(); ++i) local[vertices_[i]] = static_cast<int>(i);
  std::vector<std::int64_t> faces;
  std::set<std::pair<int, int>> edges;
  for (int f : garmentFaces) {
    int corner[3];
    for (int k = 0; k < 3; ++k) corner[k] = local[garment.mesh.F(f, k)];
    if (corner[0] < 0 || corner[1] < 0 || corner[2] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      faces.push_back(corner[k]);
      edges.insert(std::minmax(corner[k], corner[(k + 1) % 3]));
    }
  }
  faces_ = torch::tensor(faces, torch::kInt64).reshape({-1, 3});
  std::vector<std::int64_t> flat;
  for (const auto& [a, b] : edges) flat.insert(flat.end(), {a, b});
  edges_ = torch::tensor(flat, torch::kInt64).reshape({-1, 2});
}

std::unique_ptr<Target> wholeImageTarget(const garment::Garment& garment) {
  return std::make_unique<WholeImageTarget>(garment);
}

std::unique_ptr<Target> patchCropTarget(const garment::Garment& garment, const patches::Patch& patch) {
  return std::make_unique<PatchCropTarget>(garment, patch);
}

std::unique_ptr<Target> vertexTarget(const garment::Garment& garment) { return std::make_unique<VertexTarget>(garment); }

std::unique_ptr<Target> targetOf(Architecture architecture, const garment::Garment& garment,
                                 const patches::Patch* patch) {
  switch (architecture) {
    case Architecture::Whole:
    case Architecture::Necktie: return wholeImageTarget(garment);
    case Architecture::Patch:
      PIXELCLOTH_ASSERT(patch != nullptr, "a patch target without its patch");
      return patchCropTarget(garment, *patch);
    case Architecture::FullyConnected:
    case Architecture::FullyConnectedPca: return vertexTarget(garment);
  }
  PIXELCLOTH_ASSERT(false, "unknown architecture");
  return nullptr;
}

torch::Tensor sparseRows(const Eigen::SparseMatrix<float, Eigen::RowMajor, int>& matrix, const std::vector<int>& rows,
                         const std::vector<float>& scale) {
  std::vector<std::int64_t> rowIndex, colIndex;
  std::vector<float> values;
  for (size_t i = 0; i < rows.size(); ++i)
    for (Eigen::SparseMatrix<float, Eigen::RowMajor, int>::InnerIterator it(matrix, rows[i]); it; ++it) {
      rowIndex.push_back(static_cast<std::int64_t>(i));
      colIndex.push_back(it.col());
      values.push_back(it.value() * (scale.empty() ? 1.0f : scale[rows[i]]));
    }
  const auto n = static_cast<std::int64_t>(values.size());
  const torch::Tensor indices =
      torch::stack({torch::tensor(rowIndex, torch::kInt64), torch::tensor(colIndex, torch::kInt64)}).reshape({2, n});
  return torch::sparse_coo_tensor(indices, torch::tensor(values, torch::kFloat32),
                                  {static_cast<std::int64_t>(rows.size()), matrix.cols()})
      .coalesce();
}

}  // namespace pixelcloth::learn
