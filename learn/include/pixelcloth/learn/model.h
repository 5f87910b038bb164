#pragma once

// The paper's decoders (appendix, "Networks") and the fully connected baselines of its Table 2, as plain
// specifications and a model object; LibTorch stays inside learn/'s .cpp files.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pixelcloth::learn {

/// Which network: the whole-garment decoder (pose -> 256 x 256 x 6, both sides), a patch decoder (pose -> 160 x 160
/// x 3, one enlarged patch crop), the necktie decoder (36 -> 3 x 256 x 64: 256 rows as the tie hangs in its cloth
/// image, 64 columns), or a fully connected baseline to per-vertex values, directly or through PCA coefficients.
enum class Architecture { Whole, Patch, Necktie, FullyConnected, FullyConnectedPca };

/// "whole", "patch", "necktie", "fc", "fc-pca".
const char* architectureName(Architecture architecture);
Architecture architectureFromName(const std::string& name, const std::string& context);

/// What a model maps, and how wide it is.
struct ModelSpec {
  Architecture architecture = Architecture::Patch;
  /// Multiplies every channel count of the decoders and the hidden units of the baselines (0.25 for small CPU runs);
  /// counts are rounded and kept at least 1. In (0, 4].
  double width = 1.0;
  /// The decoders' upsampling layers keep at least this many channels (or the paper's own count where it is smaller)
  /// whatever the width: scaled down with the rest, the last layers of a width-0.125 decoder had 2 channels to draw 6
  /// (docs/learning.md, "Why the decoders underfit"). 0: no floor, the plain multiplier. At width 1 it changes nothing.
  int minChannels = 16;
  /// Floats in: the pose (body::kPoseSize, body::kNecktiePoseSize for the necktie) plus any marker features. 0: the
  /// pose alone.
  int inputSize = 0;
  /// fc, fc-pca: values out, 3 per vertex of the garment (required for the baselines; unused by the decoders).
  int outputValues = 0;
  int pcaComponents = 128;  ///< fc-pca: principal components of the training split
  /// Throws InputError naming the field that is out of range.
  void validate() const;
  /// The input size once defaults are applied.
  int inputs() const;
  /// Output tensor shape of one sample: {channels, height, width} for the decoders, {values} for the baselines.
  std::vector<std::int64_t> outputShape() const;
};

/// One layer as the summary lists it.
struct LayerSummary {
  std::string name;                  ///< e.g. "conv_transpose 384->192 4x4 s2"
  std::vector<std::int64_t> output;  ///< shape of one sample after the layer
  std::int64_t parameters = 0;       ///< trainable parameters (weights, biases, BatchNorm scale and shift)
  double flops = 0;                  ///< multiply-adds times 2, one sample
};

/// A model's size: trainable parameters (PCA bases are fixed buffers, not counted), shapes, and the forward cost.
struct ModelSummary {
  ModelSpec spec;
  std::int64_t parameters = 0;
  std::vector<std::int64_t> input, output;
  double gflopForward = 0;  ///< 1e9 floating point operations of one sample's forward pass (2 per multiply-add)
  std::vector<LayerSummary> layers;
  /// {"architecture", "width", "parameters", "input", "output", "gflop_forward", "layers": [...]}.
  nlohmann::json toJson() const;
};

/// The layers of `spec`'s network and what they cost, without building it.
ModelSummary summarize(const ModelSpec& spec);

/// A network of `spec`, its weights initialised from `seed` (LibTorch's defaults under that seed), on the CPU.
class Model {
 public:
  explicit Model(const ModelSpec& spec, std::uint64_t seed = 0);
  ~Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;

  const ModelSpec& spec() const;
  /// Trainable parameters, counted on the built LibTorch module (equals summarize(spec).parameters).
  std::int64_t parameters() const;
  /// Inference (BatchNorm in eval mode, no gradients): `inputs` is batch x spec().inputs(); returns batch x the
  /// product of spec().outputShape(), each row one sample's output in C order (channel, row, column).
  Eigen::MatrixXf forward(const Eigen::MatrixXf& inputs) const;
  /// fc-pca: the fixed basis the coefficients decode through, `mean` (#values) and `components` (#components x
  /// #values, orthonormal rows), e.g. from fitPca on the training split. Throws InputError for other sizes.
  void setPcaBasis(const Eigen::VectorXf& mean, const Eigen::MatrixXf& components);

 private:
  friend struct ModelAccess;  // learn/'s training and checkpoints
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A principal component basis of rows of data.
struct PcaBasis {
  Eigen::VectorXf mean;        ///< #values
  Eigen::MatrixXf components;  ///< k x #values, orthonormal rows, by decreasing variance
  Eigen::VectorXf variance;    ///< k: variance of the data along each component
  /// Coefficients (#rows x k) of `data` (#rows x #values).
  Eigen::MatrixXf project(const Eigen::MatrixXf& data) const;
  /// Back from coefficients: mean + coefficients x components.
  Eigen::MatrixXf reconstruct(const Eigen::MatrixXf& coefficients) const;
};

/// How fitPca finds the components.
enum class PcaMethod {
  Svd,         ///< LibTorch's SVD of the centred data in double precision: exact, slow beyond a few thousand columns
  Gram,        ///< the smaller Gram matrix (X^T X or X X^T) by sgemm, its eigenvectors by LAPACK in double precision
  Randomized,  ///< a randomised range finder (Halko et al. 2011) with one power iteration, then a small eigensolve
};
/// "svd", "gram", "randomized".
const char* pcaMethodName(PcaMethod method);
PcaMethod pcaMethodFromName(const std::string& name, const std::string& context);

/// The first `components` principal components of `data` (#samples x #values; e.g. a training split's offsets, one
/// sample a row). `components` is at most min(#samples, #values). Components are signed so that each one's largest
/// entry in magnitude is positive. `seed` seeds the randomised method's test matrix.
PcaBasis fitPca(const Eigen::MatrixXf& data, int components, PcaMethod method = PcaMethod::Svd,
                std::uint64_t seed = 0);

}  // namespace pixelcloth::learn
