#pragma once

// One way of turning the networks' predictions of a frame into one garment, chosen by name: the plain mean, feathered
// weights, the mean then the PCA filter, or the mean then the GAN blender (DESIGN.md, "Stitching").

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/stitch/assemble.h"
#include "pixelcloth/stitch/gan.h"
#include "pixelcloth/stitch/pca_filter.h"

namespace pixelcloth::stitch {

enum class StitchKind { Mean, Feather, Pca, Gan };

/// A stitch mode as the command line spells it: "mean", "feather", "pca:K" (K components of a PCA filter), or
/// "gan:DIR" (a blender trained by `pixelcloth train --model gan`).
struct StitchMode {
  StitchKind kind = StitchKind::Mean;
  int components = 0;           ///< pca: K
  std::filesystem::path gan;    ///< gan: the blender's folder
  std::string name() const;     ///< as parsed, e.g. "pca:64"
};

/// Parses one mode; InputError "<context>: ..." naming what was expected otherwise.
StitchMode parseStitchMode(const std::string& text, const std::string& context);
/// Parses a comma-separated list ("mean,feather,pca:64"); at least one.
std::vector<StitchMode> parseStitchModes(const std::string& text, const std::string& context);
/// The PCA filter's sweep over k: mean, then pca:1, pca:2, pca:4, ... below `rank`, and pca:rank.
std::vector<StitchMode> pcaSweepModes(int rank);

class Stitcher {
 public:
  /// `pca` is required for a pca mode (the caller loads it and checks it against the data), ignored otherwise; a gan
  /// mode loads its blender here (InputError naming the file when it cannot).
  Stitcher(const garment::Garment& garment, StitchMode mode, std::shared_ptr<const PcaFilter> pca = nullptr);
  ~Stitcher();
  Stitcher(Stitcher&&) noexcept;

  const StitchMode& mode() const { return mode_; }
  /// The networks' outputs as one garment, batch x 3 #V: the feathered weights in feather mode, the mean otherwise.
  Eigen::MatrixXf assemble(const std::vector<learn::NetworkPrediction>& predictions) const;
  /// What follows once the base is added back (residual models): the PCA projection or the GAN blend of the
  /// assembled values (batch x 3 #V); the values unchanged for mean and feather.
  Eigen::MatrixXf refine(const Eigen::MatrixXf& values) const;

 private:
  StitchMode mode_;
  int numVertices_ = 0;
  std::unique_ptr<FeatherAssembler> feather_;
  std::shared_ptr<const PcaFilter> pca_;
  std::unique_ptr<GanBlender> gan_;
};

}  // namespace pixelcloth::stitch
