// The GAN blender: training on a patch model's stitched predictions, the sidecar, loading and blending.
#include "pixelcloth/stitch/gan.h"

#include <torch/torch.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "gan_networks.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/learn/cpu.h"
#include "pixelcloth/learn/weights_file.h"
#include "pixelcloth/stitch/evaluate.h"

namespace pixelcloth::stitch {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
using core::secondsSince;

constexpr int kEvaluationChunk = 8;  ///< images through the generator at once when blending

nlohmann::json numberOrNull(double value) {
  return std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value);
}

/// Mean per-vertex distance (cm) between positions and the true ones.
double vertexErrorCm(const Eigen::MatrixX3d& positions, const Eigen::MatrixXf& truth) {
  return core::meanVertexErrorCm(positions, truth);
}

/// The generator's blend of per-vertex values (each #V x 3), in eval mode without gradients.
std::vector<Eigen::MatrixXf> blendValues(UNetGenerator& generator, const ClothTensors& images,
                                         const std::vector<const Eigen::MatrixXf*>& values) {
  torch::NoGradGuard noGrad;
  generator->eval();
  std::vector<Eigen::MatrixXf> out;
  for (size_t first = 0; first < values.size(); first += kEvaluationChunk) {
    const std::vector<const Eigen::MatrixXf*> chunk(values.begin() + first,
                                                    values.begin() + std::min(values.size(), first + kEvaluationChunk));
    const torch::Tensor blended = generator->forward(images.images(chunk));
    for (size_t k = 0; k < chunk.size(); ++k) out.push_back(images.values(blended[k]));
  }
  return out;
}

/// Mean per-vertex error (cm) over `rows` of `values` (one per row, #V x 3 in the data's space); NaN for no rows.
double meanErrorCm(const learn::TrainingData& data, const std::vector<int>& rows,
                   const std::vector<Eigen::MatrixXf>& values) {
  if (rows.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    const Eigen::MatrixX3f v = values[k];
    sum += vertexErrorCm(learn::positionsFromValues(data.space, data.frames[rows[k]], v), data.truth[rows[k]]);
  }
  return sum / rows.size();
}

std::vector<const Eigen::MatrixXf*> pointers(const std::vector<Eigen::MatrixXf>& values) {
  std::vector<const Eigen::MatrixXf*> out;
  for (const Eigen::MatrixXf& v : values) out.push_back(&v);
  return out;
}

/// Per-channel mean and standard deviation of `images`' pixels on the mask, over every stitched training input: the
/// generator's normalisation. The standard deviation is kept at least 1 mm.
void setNormalisation(UNetGenerator& generator, const ClothTensors& images,
                      const std::vector<Eigen::MatrixXf>& inputs) {
  torch::NoGradGuard noGrad;
  torch::Tensor sum = torch::zeros({6}, torch::kFloat64), squares = torch::zeros({6}, torch::kFloat64);
  const torch::Tensor mask = images.mask().to(torch::kFloat64);
  const double count = mask[0].sum().item<double>() * inputs.size();
  for (size_t first = 0; first < inputs.size(); first += kEvaluationChunk) {
    std::vector<const Eigen::MatrixXf*> chunk;
    for (size_t k = first; k < std::min(inputs.size(), first + kEvaluationChunk); ++k) chunk.push_back(&inputs[k]);
    const torch::Tensor x = images.images(chunk).to(torch::kFloat64) * mask;
    sum += x.sum({0, 2, 3});
    squares += (x * x).sum({0, 2, 3});
  }
  const torch::Tensor mean = sum / count;
  const torch::Tensor deviation = (squares / count - mean * mean).clamp_min(0).sqrt().clamp_min(1e-3);
  generator->mean.copy_(mean.to(torch::kFloat32).view({1, 6, 1, 1}));
  generator->scale.copy_(deviation.to(torch::kFloat32).view({1, 6, 1, 1}));
}

std::string csvOf(const std::vector<GanEpoch>& epochs) {
  std::ostringstream csv;
  csv << "epoch,generator_l1_m,generator_adversarial,discriminator,regularisation_error_cm,stitched_error_cm,seconds\n";
  for (const GanEpoch& e : epochs)
    csv << e.epoch << ',' << e.generatorL1 << ',' << e.generatorAdversarial << ',' << e.discriminator << ','
        << e.regularisationErrorCm << ',' << e.stitchedErrorCm << ',' << e.seconds << '\n';
  return csv.str();
}

std::string absolutePath(const fs::path& path) { return fs::absolute(path).lexically_normal().string(); }

}  // namespace

void GanOptions::validate() const {
  PIXELCLOTH_CHECK(std::isfinite(width) && width > 0 && width <= 4, "gan: width " << width << ", expected (0, 4]");
  PIXELCLOTH_CHECK(epochs >= 1 && epochs <= 100000, "gan: " << epochs << " epochs, expected 1 to 100000");
  PIXELCLOTH_CHECK(batch >= 1 && batch <= 4096, "gan: batch " << batch << ", expected 1 to 4096");
  PIXELCLOTH_CHECK(std::isfinite(learningRate) && learningRate > 0,
                   "gan: learning rate " << learningRate << ", expected > 0");
  PIXELCLOTH_CHECK(std::isfinite(l1Weight) && l1Weight >= 0, "gan: L1 weight " << l1Weight << ", expected >= 0");
  PIXELCLOTH_CHECK(threads >= 0 && threads <= 1024, "gan: " << threads << " threads, expected 0 to 1024");
}

GanReport trainGan(const learn::TrainedModel& patchModel, const learn::TrainingData& data, const GanOptions& options,
                   const fs::path& out) {
  options.validate();
  const auto start = Clock::now();
  const std::string modelName = patchModel.folder().string();
  PIXELCLOTH_CHECK(patchModel.architecture() == learn::Architecture::Patch,
                   "gan: " << modelName << " holds a " << learn::architectureName(patchModel.architecture())
                           << " model; the blender is trained on a patch model's stitched predictions (pixelcloth "
                              "train --model patch)");
  const nlohmann::json& sidecar = patchModel.sidecar();
  PIXELCLOTH_CHECK(core::valueOr(sidecar, "dataset_manifest_crc32", std::uint64_t{0}, modelName + "/model.json") == data.manifestCrc,
                   "gan: the patch model in "
                       << modelName << " was trained on " << core::valueOr<std::string>(sidecar, "dataset", "?", modelName + "/model.json") << " (manifest CRC "
                       << core::valueOr(sidecar, "dataset_manifest_crc32", std::uint64_t{0}, modelName + "/model.json") << "), not on "
                       << data.folder.string() << " (manifest CRC " << data.manifestCrc << ")");
  PIXELCLOTH_CHECK(patchModel.space() == data.space,
                   "gan: the patch model in " << modelName << " predicts " << learn::offsetSpaceName(patchModel.space())
                                              << " values, but " << data.folder.string() << " was loaded in "
                                              << learn::offsetSpaceName(data.space));
  patchModel.checkDataset(data.info);
  PIXELCLOTH_CHECK(!data.train.empty(), "gan: " << data.folder.string() << " has no training samples");
  const ClothTensors images(data.garment, "gan: " + data.folder.string());
  const learn::ThreadScope cores(options.threads);
  learn::keepFreedMemory();

  // The inputs: the patch model's stitched predictions, made once; the targets: ground truth (base added back).
  const RowPredictions trainInputs = predictRows(patchModel, data, data.train);
  const RowPredictions regularisationInputs = predictRows(patchModel, data, data.regularisation);
  auto asMatrices = [](const RowPredictions& p) {
    std::vector<Eigen::MatrixXf> out;
    for (const Eigen::MatrixX3f& v : p.values) out.push_back(v);
    return out;
  };
  const std::vector<Eigen::MatrixXf> stitched = asMatrices(trainInputs),
                                     stitchedRegularisation = asMatrices(regularisationInputs);
  std::vector<Eigen::MatrixXf> targets(data.rows());
  for (int row : data.train) targets[row] = data.residual() ? data.values[row] + data.base[row] : data.values[row];
  const double stitchedErrorCm = meanErrorCm(data, data.regularisation, stitchedRegularisation);
  std::vector<int> trainIndex(data.rows(), -1);  // a train row's index in data.train
  for (size_t k = 0; k < data.train.size(); ++k) trainIndex[data.train[k]] = static_cast<int>(k);

  GanNetworks networks(options.width, options.learningRate, options.seed);
  setNormalisation(networks.generator, images, stitched);
  const torch::Tensor mask = images.mask();

  const std::int64_t generatorParameters = parameterCount(*networks.generator),
                     discriminatorParameters = parameterCount(*networks.discriminator);
  nlohmann::json info = {{"format", "pixelcloth.model"},
                         {"version", 1},
                         {"architecture", "gan"},
                         {"width", options.width},
                         {"image", {6, 256, 256}},
                         {"generator", "pix2pix unet_256, residual"},
                         {"discriminator", "pix2pix PatchGAN 70x70 (n_layers 3) on input and output"},
                         {"generator_parameters", generatorParameters},
                         {"discriminator_parameters", discriminatorParameters},
                         {"adversarial_loss", "bce_with_logits"},
                         {"l1_weight", options.l1Weight},
                         {"learning_rate", options.learningRate},
                         {"batch", options.batch},
                         {"seed", options.seed},
                         {"garment", data.garment.name},
                         {"vertices", data.garment.mesh.numVertices()},
                         {"space", learn::offsetSpaceName(data.space)},
                         {"patch_model", absolutePath(patchModel.folder())},
                         {"patch_model_width", core::valueOr(sidecar, "width", 0.0, modelName + "/model.json")},
                         {"dataset", absolutePath(data.folder)},
                         {"dataset_manifest_crc32", data.manifestCrc},
                         {"residual", data.residual() ? nlohmann::json{{"folder", absolutePath(data.baseFolder)},
                                                                       {"manifest_crc32", data.baseCrc}}
                                                      : nlohmann::json(nullptr)}};
  core::ensureOutputFolder(out);

  GanReport report;
  report.folder = out;
  std::mt19937_64 shuffle(options.seed);
  const int steps = static_cast<int>((data.train.size() + options.batch - 1) / options.batch);
  double bestErrorCm = std::numeric_limits<double>::infinity();
  for (int epoch = 1; epoch <= options.epochs; ++epoch) {
    const auto epochStart = Clock::now();
    std::unique_ptr<core::Progress> progress;
    progress = std::make_unique<core::Progress>(
        "train gan, epoch " + std::to_string(epoch) + "/" + std::to_string(options.epochs) + ", steps", steps);
    std::vector<int> order = data.train;
    for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[shuffle() % i]);
    GanEpoch record;
    record.epoch = epoch;
    for (size_t first = 0; first < order.size(); first += options.batch) {
      std::vector<const Eigen::MatrixXf*> x, y;
      for (size_t k = first; k < std::min(order.size(), first + options.batch); ++k) {
        x.push_back(&stitched[trainIndex[order[k]]]);
        y.push_back(&targets[order[k]]);
      }
      const GanStepLosses losses = networks.step(images.images(x), images.images(y), mask, options.l1Weight);
      record.generatorL1 += losses.l1 / steps;
      record.generatorAdversarial += losses.adversarial / steps;
      record.discriminator += losses.discriminator / steps;
      if (progress) progress->advance();
    }
    if (progress) progress->finish();
    record.stitchedErrorCm = stitchedErrorCm;
    record.regularisationErrorCm = meanErrorCm(
        data, data.regularisation,
        data.regularisation.empty() ? std::vector<Eigen::MatrixXf>()
                                    : blendValues(networks.generator, images, pointers(stitchedRegularisation)));
    record.seconds = secondsSince(epochStart);
    report.epochs.push_back(record);
    // Model selection on the regularisation split (the test split is only for reporting); without one, the last.
    if (data.regularisation.empty() || record.regularisationErrorCm < bestErrorCm) {
      bestErrorCm = record.regularisationErrorCm;
      report.bestEpoch = epoch;
      learn::saveModuleWeights(*networks.generator, out / "model.tensors");
      info["epoch"] = epoch;
      info["regularisation_error_cm"] = numberOrNull(record.regularisationErrorCm);
      info["stitched_regularisation_error_cm"] = numberOrNull(stitchedErrorCm);
      info["generator_l1_m"] = record.generatorL1;
      core::writeJson(out / "model.json", info);
    }
    core::writeTextAtomically(out / "log.csv", csvOf(report.epochs));
    PIXELCLOTH_INFO("train gan: epoch " << epoch << "/" << options.epochs << ": L1 " << record.generatorL1 * 100
                                        << " cm, adversarial " << record.generatorAdversarial << ", discriminator "
                                        << record.discriminator << "; regularisation " << record.regularisationErrorCm
                                        << " cm blended, " << stitchedErrorCm << " cm stitched; " << record.seconds
                                        << " s");
  }
  report.seconds = secondsSince(start);
  return report;
}

struct GanBlender::Impl {
  fs::path folder;
  nlohmann::json info;
  std::unique_ptr<ClothTensors> images;
  UNetGenerator generator{nullptr};
};

GanBlender::GanBlender(const fs::path& folder, const garment::Garment& garment) : impl_(std::make_unique<Impl>()) {
  impl_->folder = folder;
  const fs::path jsonPath = folder / "model.json", weightsPath = folder / "model.tensors";
  const std::string context = jsonPath.string();
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(jsonPath, ec),
                   context << ": no such file (a GAN blender folder from pixelcloth train --model gan has model.json "
                              "and model.tensors)");
  impl_->info = core::readJson(jsonPath);
  const nlohmann::json& info = impl_->info;
  const std::string format = core::valueOr<std::string>(info, "format", "", context);
  PIXELCLOTH_CHECK(info.is_object() && format == "pixelcloth.model",
                   context << ": not a pixelcloth model (format '" << format << "')");
  const std::string architecture = core::requireValue<std::string>(info, "architecture", context);
  PIXELCLOTH_CHECK(architecture == "gan",
                   context << ": a " << architecture << " model, expected a GAN blender (architecture gan)");
  const double width = core::requireValue<double>(info, "width", context);
  PIXELCLOTH_CHECK(std::isfinite(width) && width > 0 && width <= 4,
                   context << ": width " << width << ", expected (0, 4]");
  const std::string garmentName = core::requireValue<std::string>(info, "garment", context);
  const int vertices = core::requireValue<int>(info, "vertices", context);
  PIXELCLOTH_CHECK(garmentName == garment.name && vertices == garment.mesh.numVertices(),
                   context << ": a blender of the " << garmentName << " with " << vertices << " vertices, not of this "
                           << garment.name << " with " << garment.mesh.numVertices());
  impl_->images = std::make_unique<ClothTensors>(garment, context);

  impl_->generator = UNetGenerator(width);
  PIXELCLOTH_CHECK(fs::is_regular_file(weightsPath, ec), weightsPath.string()
                                                             << ": no such file (the weights of the GAN blender "
                                                             << context << " describes)");
  learn::loadModuleWeights(*impl_->generator, weightsPath,
                           "a GAN generator of width " + std::to_string(width) + " (" + context + ")");
  PIXELCLOTH_CHECK(
      impl_->generator->scale.gt(0).all().item<bool>() && impl_->generator->mean.isfinite().all().item<bool>(),
      weightsPath.string() << ": its normalisation (mean, scale) is not finite and positive");
  impl_->generator->eval();
}

GanBlender::~GanBlender() = default;
GanBlender::GanBlender(GanBlender&&) noexcept = default;

Eigen::MatrixXf GanBlender::blend(const Eigen::MatrixXf& stitched) const {
  const int V = impl_->images->imager().numVertices();
  PIXELCLOTH_CHECK(stitched.cols() == 3 * V && stitched.rows() > 0,
                   "blend: " << stitched.rows() << " x " << stitched.cols() << " values, expected batch x " << 3 * V
                             << " (3 per vertex of the " << core::valueOr<std::string>(impl_->info, "garment", "?", "blend: the blender's model.json") << ")");
  PIXELCLOTH_CHECK(stitched.allFinite(), "blend: the stitched values are not all finite");
  std::vector<Eigen::MatrixXf> rows;
  for (Eigen::Index k = 0; k < stitched.rows(); ++k) {
    Eigen::MatrixXf values(V, 3);
    for (int v = 0; v < V; ++v) values.row(v) = stitched.block<1, 3>(k, 3 * v);
    rows.push_back(std::move(values));
  }
  const std::vector<Eigen::MatrixXf> blended = blendValues(impl_->generator, *impl_->images, pointers(rows));
  Eigen::MatrixXf out(stitched.rows(), stitched.cols());
  for (Eigen::Index k = 0; k < stitched.rows(); ++k)
    for (int v = 0; v < V; ++v) out.block<1, 3>(k, 3 * v) = blended[k].row(v);
  return out;
}

const nlohmann::json& GanBlender::info() const { return impl_->info; }
const fs::path& GanBlender::folder() const { return impl_->folder; }

nlohmann::json ganSummary(double width) {
  GanOptions options;
  options.width = width;
  options.validate();
  torch::NoGradGuard noGrad;
  UNetGenerator generator(width);
  PatchDiscriminator discriminator(width);
  generator->eval();
  discriminator->eval();
  std::vector<std::vector<std::int64_t>> generatorShapes, discriminatorShapes;
  const torch::Tensor output = generator->forward(torch::zeros({1, 6, 256, 256}), &generatorShapes);
  const torch::Tensor logits = discriminator->forward(torch::zeros({1, 12, 256, 256}), &discriminatorShapes);
  auto layers = [](const std::vector<std::vector<std::int64_t>>& shapes, const std::vector<std::string>& names) {
    nlohmann::json list = nlohmann::json::array();
    for (size_t k = 0; k < shapes.size(); ++k) list.push_back({{"name", names[k]}, {"output", shapes[k]}});
    return list;
  };
  std::vector<std::string> generatorNames;
  for (int i = 1; i <= 8; ++i) generatorNames.push_back("down" + std::to_string(i));
  for (int i = 8; i >= 1; --i) generatorNames.push_back("up" + std::to_string(i));
  return {{"width", width},
          {"generator",
           {{"parameters", parameterCount(*generator)},
            {"input", {6, 256, 256}},
            {"output", output.sizes().slice(1).vec()},
            {"layers", layers(generatorShapes, generatorNames)}}},
          {"discriminator",
           {{"parameters", parameterCount(*discriminator)},
            {"input", {12, 256, 256}},
            {"output", logits.sizes().slice(1).vec()},
            {"layers", layers(discriminatorShapes, {"conv1", "conv2", "conv3", "conv4", "conv5"})}}}};
}

}  // namespace pixelcloth::stitch
