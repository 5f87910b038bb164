#pragma once

// Fast inference of trained networks on the CPU (DESIGN.md, "Inference"): the networks of a model (the 28 patch
// decoders of a frame, or one whole-garment, necktie or baseline network) compiled once into oneDNN primitives, like a
// prefactored solver, then run on batches of frames. LibTorch's eval-mode forward stays the reference.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "pixelcloth/learn/model.h"

namespace pixelcloth::learn {

/// Which implementation runs inference: LibTorch's modules (the reference) or the oneDNN networks below.
enum class Engine { LibTorch, OneDnn };

/// "libtorch", "onednn".
const char* engineName(Engine engine);
Engine engineFromName(const std::string& name, const std::string& context);

/// Row-major float rows: one sample a row.
using RowsF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Networks of one spec compiled for inference. At construction every BatchNorm is folded into the layer before it
/// and the weights are copied out of the models; the first forward() at a batch size makes its oneDNN primitives
/// and reorders the weights into the layouts the kernels chose, later calls at that size only run them.
///
///   std::vector<const Model*> decoders = ...;            // e.g. the 28 patch decoders of a model folder
///   CompiledNetworks compiled(decoders);
///   std::vector<RowsF> images;
///   compiled.forward(poses, images);                   // images[p]: batch x 3*160*160 of patch p
class CompiledNetworks {
 public:
  /// `models` share one spec (InputError otherwise); they may be destroyed afterwards. `threads` (0: every core)
  /// is how many cores a forward() keeps busy: networks are spread over them, one thread each, when there are at
  /// least as many networks as threads; a single network runs on all of them.
  explicit CompiledNetworks(const std::vector<const Model*>& models, int threads = 0);
  ~CompiledNetworks();
  CompiledNetworks(CompiledNetworks&&) noexcept;
  CompiledNetworks& operator=(CompiledNetworks&&) noexcept;

  const ModelSpec& spec() const;
  int size() const;  ///< networks
  int threads() const;

  /// outputs[n] (resized to batch x the product of spec().outputShape(), C order per row) is network n's output
  /// for `inputs` (batch x spec().inputs()): Model::forward's values up to float rounding. Not for concurrent use
  /// from several threads.
  void forward(const RowsF& inputs, std::vector<RowsF>& outputs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pixelcloth::learn
