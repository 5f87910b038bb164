#include "pixelcloth/patches/cloth_image.h"

#include <algorithm>
#include <cmath>

#include "pixelcloth/core/error.h"

namespace pixelcloth::patches {

namespace {
std::string sourceName(const std::string& source) { return source.empty() ? "cloth image" : source; }

std::string layerList(const std::vector<ClothLayer>& layers) {
  std::string out;
  for (const ClothLayer& l : layers) out += (out.empty() ? "" : ", ") + ("'" + l.name + "'");
  return out.empty() ? "none" : out;
}

std::string prefix(const std::string& layer) { return layer.empty() ? "" : layer + "."; }
}  // namespace

const ClothLayer& ClothImage::layer(const std::string& name) const {
  for (const ClothLayer& l : layers)
    if (l.name == name) return l;
  PIXELCLOTH_FAIL(sourceName(source) << ": no layer '" << name << "'; the layers are " << layerList(layers));
}

ClothLayer& ClothImage::layer(const std::string& name) {
  return const_cast<ClothLayer&>(static_cast<const ClothImage&>(*this).layer(name));
}

void ClothImage::validate() const {
  PIXELCLOTH_CHECK(width > 0 && height > 0 && !layers.empty(), sourceName(source)
                                                                   << ": empty cloth image (" << width << " x "
                                                                   << height << ", " << layers.size() << " layers)");
  for (const ClothLayer& l : layers)
    for (const Eigen::MatrixXf* c : {&l.du, &l.dv, &l.dn, &l.mask})
      PIXELCLOTH_CHECK(c->rows() == height && c->cols() == width,
                       sourceName(source) << ": layer '" << l.name << "' has a " << c->cols() << " x " << c->rows()
                                          << " channel, expected " << width << " x " << height);
}

core::ExrImage ClothImage::toExr() const {
  validate();
  core::ExrImage exr;
  for (const ClothLayer& l : layers) {
    exr.addChannel(prefix(l.name) + "du", l.du);
    exr.addChannel(prefix(l.name) + "dv", l.dv);
    exr.addChannel(prefix(l.name) + "dn", l.dn);
    exr.addChannel(prefix(l.name) + "mask", l.mask);
  }
  return exr;
}

ClothImage ClothImage::fromExr(const core::ExrImage& exr) {
  ClothImage image;
  image.width = exr.width;
  image.height = exr.height;
  image.source = exr.source;
  std::vector<std::string> names;
  for (const std::string& c : exr.channelNames) {
    if (c == "du") names.push_back("");
    if (c.size() > 3 && c.compare(c.size() - 3, 3, ".du") == 0) names.push_back(c.substr(0, c.size() - 3));
  }
  // Keep the garment's usual order when the file sorted the channels by name ("back" < "front").
  std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    auto rank = [](const std::string& n) { return n == "front" ? 0 : n == "back" ? 1 : 2; };
    return std::make_pair(rank(a), a) < std::make_pair(rank(b), b);
  });
  std::string channels;
  for (const std::string& c : exr.channelNames) channels += (channels.empty() ? "" : ", ") + c;
  PIXELCLOTH_CHECK(!names.empty(), sourceName(exr.source)
                                       << ": not a cloth image: no 'du' or '<layout>.du' channel "
                                       << "(channels: " << (channels.empty() ? "none" : channels) << ")");
  for (const std::string& name : names) {
    ClothLayer layer;
    layer.name = name;
    layer.du = exr.channel(prefix(name) + "du");
    layer.dv = exr.channel(prefix(name) + "dv");
    layer.dn = exr.channel(prefix(name) + "dn");
    layer.mask = exr.channel(prefix(name) + "mask");
    image.layers.push_back(std::move(layer));
  }
  image.validate();
  for (const ClothLayer& l : image.layers) {  // the first NaN or infinity, row by row
    const std::pair<const Eigen::MatrixXf*, const char*> channels[] = {
        {&l.du, "du"}, {&l.dv, "dv"}, {&l.dn, "dn"}, {&l.mask, "mask"}};
    for (const auto& [c, channel] : channels) {
      if (c->allFinite()) continue;
      for (Eigen::Index y = 0; y < c->rows(); ++y)
        for (Eigen::Index x = 0; x < c->cols(); ++x)
          PIXELCLOTH_CHECK(std::isfinite((*c)(y, x)),
                           sourceName(image.source) << ": channel '" << prefix(l.name) << channel << "' is " << (*c)(y, x)
                                                    << " at row " << y + 1 << ", column " << x + 1
                                                    << " (counting from 1); expected finite numbers");
    }
  }
  return image;
}

void writeClothImage(const std::filesystem::path& path, const ClothImage& image) {
  core::writeExr(path, image.toExr());
}

ClothImage readClothImage(const std::filesystem::path& path) {
  core::ExrImage exr = core::readExr(path);
  exr.source = path.string();
  return ClothImage::fromExr(exr);
}

ImageFrame clothImageFrame(const garment::Garment& garment, int layout, int width, int height, double margin) {
  PIXELCLOTH_CHECK(layout >= 0 && layout < garment.numLayouts(),
                   garment.name << ": layout " << layout << " does not exist (" << garment.numLayouts() << " layouts)");
  PIXELCLOTH_CHECK(width > 0 && height > 0, "image size must be positive, got " << width << " x " << height);
  PIXELCLOTH_CHECK(margin >= 0 && margin < 0.5, "image margin must be in [0, 0.5), got " << margin);
  double metresPerPixel = 0;
  for (int l = 0; l < garment.numLayouts(); ++l) {
    Eigen::Vector2d size = garment.layoutBounds(l).sizes();
    metresPerPixel = std::max(
        {metresPerPixel, size.x() / ((1.0 - 2.0 * margin) * width), size.y() / ((1.0 - 2.0 * margin) * height)});
  }
  ImageFrame frame;
  frame.width = width;
  frame.height = height;
  frame.metresPerPixel = metresPerPixel;
  Eigen::Vector2d centre = garment.layoutBounds(layout).center();
  frame.topLeft = {centre.x() - 0.5 * width * metresPerPixel, centre.y() + 0.5 * height * metresPerPixel};
  return frame;
}

void ClothImageOptions::validate() const {
  PIXELCLOTH_CHECK(width >= 0 && width <= 8192, "cloth image width must be in [1, 8192] (0: default), got " << width);
  PIXELCLOTH_CHECK(height >= 0 && height <= 8192,
                   "cloth image height must be in [1, 8192] (0: default), got " << height);
  RasterOptions{padding}.validate();
  PIXELCLOTH_CHECK(margin >= 0 && margin < 0.5, "cloth image margin must be in [0, 0.5), got " << margin);
}

ClothImager::ClothImager(const garment::Garment& garment, const ClothImageOptions& options) {
  options.validate();
  width_ = options.width > 0 ? options.width : garment.traits.imageWidth;
  height_ = options.height > 0 ? options.height : garment.traits.imageHeight;
  numVertices_ = garment.mesh.numVertices();
  garmentName_ = garment.name;
  layouts_ = garment.layouts;
  layoutsPerVertex_ = Eigen::VectorXf::Zero(numVertices_);
  for (int l = 0; l < garment.numLayouts(); ++l) {
    ImageFrame frame = clothImageFrame(garment, l, width_, height_, options.margin);
    rasters_.push_back(buildRaster(garment, l, frame, RasterOptions{options.padding}));
    samplers_.push_back(buildSample(garment, rasters_.back()));
    for (int v : rasters_.back().vertices) layoutsPerVertex_[v] += 1;
  }
}

ClothImage ClothImager::rasterize(const Eigen::Ref<const Eigen::MatrixXf>& offsets) const {
  PIXELCLOTH_CHECK(offsets.rows() == numVertices_ && offsets.cols() == 3,
                   garmentName_ << ": offsets are " << offsets.rows() << " x " << offsets.cols() << ", expected "
                                << numVertices_ << " x 3 (du, dv, dn per vertex)");
  ClothImage image;
  image.width = width_;
  image.height = height_;
  Eigen::MatrixXf pixels;
  for (size_t l = 0; l < rasters_.size(); ++l) {
    rasters_[l].applyTo(offsets, pixels);
    ClothLayer layer;
    layer.name = layouts_[l];
    layer.du = toImage(pixels.col(0), width_, height_);
    layer.dv = toImage(pixels.col(1), width_, height_);
    layer.dn = toImage(pixels.col(2), width_, height_);
    layer.mask = rasters_[l].maskImage();
    image.layers.push_back(std::move(layer));
  }
  return image;
}

Eigen::MatrixXf ClothImager::sample(const ClothImage& image) const {
  image.validate();
  const std::string name = sourceName(image.source);
  PIXELCLOTH_CHECK(image.width == width_ && image.height == height_,
                   name << ": image is " << image.width << " x " << image.height << ", the " << garmentName_
                        << " cloth image is " << width_ << " x " << height_);
  Eigen::MatrixXf sum = Eigen::MatrixXf::Zero(numVertices_, 3);
  for (size_t l = 0; l < samplers_.size(); ++l) {
    // A single-layout garment also accepts an image with unprefixed channels (layer "").
    const ClothLayer* layer = nullptr;
    for (const ClothLayer& candidate : image.layers)
      if (candidate.name == layouts_[l] || (layouts_.size() == 1 && image.layers.size() == 1 && candidate.name.empty()))
        layer = &candidate;
    if (!layer) image.layer(layouts_[l]);  // throws, naming the file and the layers present
    Eigen::MatrixXf pixels(static_cast<Eigen::Index>(width_) * height_, 3);
    pixels.col(0) = fromImage(layer->du);
    pixels.col(1) = fromImage(layer->dv);
    pixels.col(2) = fromImage(layer->dn);
    sum += samplers_[l].apply(pixels);
  }
  return (sum.array().colwise() / layoutsPerVertex_.array().max(1.0f)).matrix();
}

PatchCrop cropFrame(const garment::Garment& garment, const Patch& patch, int imageSize, int cropSize,
                    const RasterOptions& options) {
  PIXELCLOTH_CHECK(imageSize > 0 && cropSize > 0 && cropSize <= 8192,
                   "patch crop: image size and crop size must be positive, got " << imageSize << " and " << cropSize);
  PIXELCLOTH_CHECK(!patch.faces.empty(), garment.name << ": patch " << patch.id << " has no faces");
  ImageFrame full = layoutFrame(garment, patch.layout, imageSize);
  Eigen::AlignedBox2d box;
  for (int f : patch.faces)
    for (int k = 0; k < 3; ++k) box.extend(garment.mesh.UV.row(garment.mesh.FUV(f, k)).transpose());
  Eigen::Vector2d centre = full.toPixel(box.center());
  PatchCrop crop;
  crop.origin = {static_cast<int>(std::lround(centre.x() - 0.5 * cropSize)),
                 static_cast<int>(std::lround(centre.y() - 0.5 * cropSize))};
  crop.frame.width = crop.frame.height = cropSize;
  crop.frame.metresPerPixel = full.metresPerPixel;
  crop.frame.topLeft = full.toPattern(crop.origin.cast<double>());
  crop.raster = buildRaster(garment, patch.layout, patch.faces, crop.frame, options);
  return crop;
}

std::vector<int> enlargedPatchFaces(const garment::Garment& garment, const Patch& patch, const ImageFrame& frame,
                                    double context) {
  PIXELCLOTH_CHECK(context >= 0, "enlarged patch: context " << context << " px, expected >= 0");
  const core::Mesh& mesh = garment.mesh;
  std::vector<Eigen::Vector2d> own;
  for (int f : patch.faces)
    for (int k = 0; k < 3; ++k) own.push_back(frame.toPixel(mesh.UV.row(mesh.FUV(f, k)).transpose()));
  std::sort(own.begin(), own.end(), [](const auto& a, const auto& b) { return a.x() < b.x(); });
  // Nearest corner of the patch, by a sweep over x: corners are sorted, so only those within `context` in x count.
  auto near = [&](const Eigen::Vector2d& p) {
    auto first = std::lower_bound(own.begin(), own.end(), p.x() - context,
                                  [](const Eigen::Vector2d& a, double x) { return a.x() < x; });
    for (auto it = first; it != own.end() && it->x() <= p.x() + context; ++it)
      if ((*it - p).squaredNorm() <= context * context) return true;
    return false;
  };
  std::vector<int> faces;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    if (garment.faceLayout(f) != patch.layout) continue;
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) inside = near(frame.toPixel(mesh.UV.row(mesh.FUV(f, k)).transpose()));
    if (inside) faces.push_back(f);
  }
  return faces;
}

EnlargedCrop enlargedCrop(const garment::Garment& garment, const Patch& patch) {
  EnlargedCrop crop;
  crop.frame = cropFrame(garment, patch).frame;
  crop.faces = enlargedPatchFaces(garment, patch, crop.frame);
  crop.raster = buildRaster(garment, patch.layout, crop.faces, crop.frame, RasterOptions{4});
  crop.sample = buildSample(garment, crop.raster);
  return crop;
}

}  // namespace pixelcloth::patches
