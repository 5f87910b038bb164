#include "pixelcloth/stitch/stitcher.h"

#include <sstream>

#include "pixelcloth/core/error.h"

namespace pixelcloth::stitch {

std::string StitchMode::name() const {
  switch (kind) {
    case StitchKind::Mean: return "mean";
    case StitchKind::Feather: return "feather";
    case StitchKind::Pca: return "pca:" + std::to_string(components);
    case StitchKind::Gan: return "gan:" + gan.string();
  }
  return "unknown";
}

std::vector<StitchMode> pcaSweepModes(int rank) {
  std::vector<StitchMode> modes(1);
  for (int k = 1; k < rank; k *= 2) modes.push_back({StitchKind::Pca, k, {}});
  modes.push_back({StitchKind::Pca, rank, {}});
  return modes;
}

StitchMode parseStitchMode(const std::string& text, const std::string& context) {
  StitchMode mode;
  if (text == "mean") return mode;
  if (text == "feather") {
    mode.kind = StitchKind::Feather;
    return mode;
  }
  if (text.rfind("pca:", 0) == 0) {
    const std::string k = text.substr(4);
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(k, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    PIXELCLOTH_CHECK(!k.empty() && used == k.size() && value >= 1,
                     context << ": '" << text << "': expected pca:K with K a positive number of components, e.g. pca:64");
    mode.kind = StitchKind::Pca;
    mode.components = value;
    return mode;
  }
  if (text.rfind("gan:", 0) == 0 && text.size() > 4) {
    mode.kind = StitchKind::Gan;
    mode.gan = text.substr(4);
    return mode;
  }
  PIXELCLOTH_FAIL(context << ": unknown stitch mode '" << text
                          << "'; expected mean, feather, pca:K (K components) or gan:DIR (a blender's folder)");
}

std::vector<StitchMode> parseStitchModes(const std::string& text, const std::string& context) {
  std::vector<StitchMode> modes;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) modes.push_back(parseStitchMode(item, context));
  PIXELCLOTH_CHECK(!modes.empty(), context << ": no stitch mode; expected e.g. mean or mean,feather,pca:64");
  return modes;
}

Stitcher::Stitcher(const garment::Garment& garment, StitchMode mode, std::shared_ptr<const PcaFilter> pca)
    : mode_(std::move(mode)), numVertices_(garment.mesh.numVertices()) {
  switch (mode_.kind) {
    case StitchKind::Mean: break;
    case StitchKind::Feather: feather_ = std::make_unique<FeatherAssembler>(garment); break;
    case StitchKind::Pca:
      PIXELCLOTH_CHECK(pca != nullptr, mode_.name() << ": no PCA filter given");
      pca_ = std::move(pca);
      PIXELCLOTH_CHECK(mode_.components <= pca_->rank(),
                       mode_.name() << ": the PCA filter" << (pca_->folder().empty() ? "" : " in " + pca_->folder().string())
                                    << " was fitted with rank " << pca_->rank() << ", expected K from 1 to "
                                    << pca_->rank());
      break;
    case StitchKind::Gan: gan_ = std::make_unique<GanBlender>(mode_.gan, garment); break;
  }
}

Stitcher::~Stitcher() = default;
Stitcher::Stitcher(Stitcher&&) noexcept = default;

Eigen::MatrixXf Stitcher::assemble(const std::vector<learn::NetworkPrediction>& predictions) const {
  return feather_ ? feather_->assemble(predictions) : assembleMean(predictions, numVertices_);
}

Eigen::MatrixXf Stitcher::refine(const Eigen::MatrixXf& values) const {
  if (pca_) return pca_->filter(values, mode_.components);
  if (gan_) return gan_->blend(values);
  return values;
}

}  // namespace pixelcloth::stitch
