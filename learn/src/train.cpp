// Training a whole-garment image decoder on a dataset's cloth images, its checkpoint, and prediction.
#include "pixelcloth/learn/train.h"

#include <torch/torch.h>

#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

#include "losses.h"
#include "model_impl.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/patches/cloth_image.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace fs = std::filesystem;

namespace {

/// The cloth images of one garment as tensors: channels (du, dv, dn) per layout, C x H x W.
class ImageCodec {
 public:
  explicit ImageCodec(const garment::Garment& garment)
      : imager_(garment), blank_(imager_.rasterize(Eigen::MatrixXf::Zero(garment.mesh.numVertices(), 3))) {
    const int L = static_cast<int>(blank_.layers.size());
    mask_ = torch::zeros({3 * L, blank_.height, blank_.width});
    for (int l = 0; l < L; ++l)
      for (int c = 0; c < 3; ++c) mask_[3 * l + c].copy_(toTensor(blank_.layers[l].mask).gt(0.5));
  }

  std::vector<std::int64_t> shape() const { return {mask_.size(0), mask_.size(1), mask_.size(2)}; }
  /// 1 on the padded UV mask (cloth and padding), 0 on empty pixels: C x H x W.
  const torch::Tensor& mask() const { return mask_; }

  /// The cloth image of per-vertex offsets (#V x 3): C x H x W.
  torch::Tensor image(const Eigen::MatrixXf& offsets) const {
    const patches::ClothImage image = imager_.rasterize(offsets);
    std::vector<torch::Tensor> channels;
    for (const patches::ClothLayer& layer : image.layers)
      for (const Eigen::MatrixXf* channel : {&layer.du, &layer.dv, &layer.dn})
        channels.push_back(toTensor(*channel));
    return torch::stack(channels);
  }

  /// Per-vertex offsets (#V x 3) sampled from an image (C x H x W), as the cloth pixels see it.
  Eigen::MatrixXf offsets(const torch::Tensor& image) const {
    patches::ClothImage predicted = blank_;
    const torch::Tensor cpu = image.to(torch::kCPU, torch::kFloat32).contiguous();
    for (size_t l = 0; l < predicted.layers.size(); ++l) {
      patches::ClothLayer& layer = predicted.layers[l];
      Eigen::MatrixXf* channels[3] = {&layer.du, &layer.dv, &layer.dn};
      for (int c = 0; c < 3; ++c) *channels[c] = toEigen(cpu[3 * l + c]);
    }
    return imager_.sample(predicted);
  }

 private:
  patches::ClothImager imager_;
  patches::ClothImage blank_;
  torch::Tensor mask_;
};

/// Mean per-vertex distance (cm) between predicted and stored offsets over `rows` (frames are orthonormal, so it is the
/// position error); NaN for no rows.
double vertexErrorCm(torch::nn::Sequential& net, const ImageCodec& codec, const data::Dataset& dataset,
                     const std::vector<int>& rows) {
  if (rows.empty()) return std::numeric_limits<double>::quiet_NaN();
  torch::NoGradGuard noGrad;
  net->eval();
  double sum = 0;
  for (size_t first = 0; first < rows.size(); first += 16) {
    const size_t count = std::min<size_t>(16, rows.size() - first);
    Eigen::MatrixXf poses(count, dataset.info.settings.poseSize);
    for (size_t k = 0; k < count; ++k) poses.row(k) = dataset.pose(rows[first + k]).transpose();
    const torch::Tensor predicted = net->forward(toTensor(poses));
    for (size_t k = 0; k < count; ++k)
      sum += (codec.offsets(predicted[k]) - dataset.offsetsOf(rows[first + k])).rowwise().norm().mean();
  }
  return 100 * sum / rows.size();
}

std::string csvOf(const std::vector<EpochRecord>& epochs) {
  std::ostringstream csv;
  csv << "epoch,loss,train_error_cm,regularisation_error_cm,seconds\n";
  for (const EpochRecord& e : epochs)
    csv << e.epoch << ',' << e.loss << ',' << e.trainErrorCm << ',' << e.regularisationErrorCm << ',' << e.seconds
        << '\n';
  return csv.str();
}

void saveWeights(const torch::nn::Sequential& net, const fs::path& path) {
  torch::serialize::OutputArchive archive;
  net->save(archive);
  core::writeAtomically(path, [&](const fs::path& temporary) { archive.save_to(temporary.string()); });
}

}  // namespace

void TrainOptions::validate() const {
  model.validate();
  PIXELCLOTH_CHECK(
      model.architecture == Architecture::Whole || model.architecture == Architecture::Necktie,
      "train: the " << architectureName(model.architecture) << " model is not trainable yet; whole and necktie are");
  PIXELCLOTH_CHECK(loss == "l1" || loss == "l2", "train: loss '" << loss << "', expected l1 or l2");
  PIXELCLOTH_CHECK(epochs >= 1 && epochs <= 100000, "train: " << epochs << " epochs, expected 1 to 100000");
  PIXELCLOTH_CHECK(batch >= 1 && batch <= 4096, "train: batch " << batch << ", expected 1 to 4096");
  PIXELCLOTH_CHECK(std::isfinite(learningRate) && learningRate > 0,
                   "train: learning rate " << learningRate << ", expected > 0");
}

TrainReport trainImageModel(const fs::path& datasetFolder, const fs::path& out, const TrainOptions& options) {
  options.validate();
  const data::Dataset dataset = data::openDataset(datasetFolder);
  const garment::Garment garment = data::datasetGarment(dataset.info);
  const ImageCodec codec(garment);
  PIXELCLOTH_CHECK(options.model.outputShape() == codec.shape(),
                   "train: the " << architectureName(options.model.architecture) << " model predicts "
                                 << core::npyShapeString(options.model.outputShape()) << " images; "
                                 << datasetFolder.string() << " holds the " << garment.name << ", whose images are "
                                 << core::npyShapeString(codec.shape()));
  PIXELCLOTH_CHECK(options.model.inputs() == dataset.info.settings.poseSize,
                   "train: the model takes " << options.model.inputs() << " floats, the poses of "
                                             << datasetFolder.string() << " have " << dataset.info.settings.poseSize);
  const std::vector<int> train = dataset.rowsOf(data::Split::Train),
                         regularisation = dataset.rowsOf(data::Split::Regularisation);
  PIXELCLOTH_CHECK(!train.empty(), "train: " << datasetFolder.string() << " has no training samples");
  core::ensureOutputFolder(out);

  Model model(options.model, options.seed);
  torch::nn::Sequential& net = ModelAccess::network(model);
  torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(options.learningRate));
  const ImageLoss loss = options.loss == "l2" ? ImageLoss::L2 : ImageLoss::L1;
  const nlohmann::json sidecar = {{"format", "pixelcloth.model"},
                                  {"version", 1},
                                  {"architecture", architectureName(options.model.architecture)},
                                  {"width", options.model.width},
                                  {"inputs", options.model.inputs()},
                                  {"output", options.model.outputShape()},
                                  {"garment", garment.name},
                                  {"offsets", "local"},
                                  {"loss", options.loss},
                                  {"dataset", fs::absolute(datasetFolder).string()},
                                  {"dataset_manifest_crc32", data::fileCrc32(datasetFolder / "manifest.json")}};
  TrainReport report;
  std::mt19937_64 shuffle(options.seed);
  std::unique_ptr<core::Progress> progress;
  if (!options.quiet) progress = std::make_unique<core::Progress>("train", options.epochs);
  for (int epoch = 1; epoch <= options.epochs; ++epoch) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<int> order = train;
    for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[shuffle() % i]);
    net->train();
    double lossSum = 0;
    int steps = 0;
    for (size_t first = 0; first < order.size(); first += options.batch) {
      const size_t count = std::min<size_t>(options.batch, order.size() - first);
      Eigen::MatrixXf poses(count, dataset.info.settings.poseSize);
      std::vector<torch::Tensor> targets;
      for (size_t k = 0; k < count; ++k) {
        poses.row(k) = dataset.pose(order[first + k]).transpose();
        targets.push_back(codec.image(dataset.offsetsOf(order[first + k])));
      }
      const torch::Tensor predicted = net->forward(toTensor(poses));
      const torch::Tensor value = maskedImageLoss(predicted, torch::stack(targets), codec.mask().unsqueeze(0), loss);
      adam.zero_grad();
      value.backward();
      adam.step();
      lossSum += value.item<double>();
      ++steps;
    }
    EpochRecord record;
    record.epoch = epoch;
    record.loss = lossSum / steps;
    record.trainErrorCm = vertexErrorCm(net, codec, dataset, train);
    record.regularisationErrorCm = vertexErrorCm(net, codec, dataset, regularisation);
    record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.epochs.push_back(record);
    // Model selection on the regularisation split (the test split is only for reporting); without one, the last.
    const double selection = regularisation.empty() ? -epoch : record.regularisationErrorCm;
    if (report.bestEpoch == 0 || selection < (regularisation.empty() ? -report.bestEpoch : report.bestErrorCm)) {
      report.bestEpoch = epoch;
      report.bestErrorCm = regularisation.empty() ? record.trainErrorCm : record.regularisationErrorCm;
      saveWeights(net, out / "model.pt");
      nlohmann::json json = sidecar;
      json["epoch"] = epoch;
      json["train_error_cm"] = record.trainErrorCm;
      json["regularisation_error_cm"] = std::isnan(record.regularisationErrorCm)
                                            ? nlohmann::json(nullptr)
                                            : nlohmann::json(record.regularisationErrorCm);
      core::writeJson(out / "model.json", json);
    }
    core::writeTextAtomically(out / "log.csv", csvOf(report.epochs));
    if (progress) progress->advance();
  }
  if (progress) progress->finish();
  return report;
}

Model loadModel(const fs::path& folder) {
  const fs::path sidecarPath = folder / "model.json", weights = folder / "model.pt";
  const nlohmann::json json = core::readJson(sidecarPath);
  const std::string context = sidecarPath.string();
  PIXELCLOTH_CHECK(core::requireValue<std::string>(json, "format", context) == "pixelcloth.model",
                   context << ": not a pixelcloth model (format '" << json["format"] << "')");
  ModelSpec spec;
  spec.architecture =
      architectureFromName(core::requireValue<std::string>(json, "architecture", context), context + ": architecture");
  spec.width = core::requireValue<double>(json, "width", context);
  spec.inputSize = core::requireValue<int>(json, "inputs", context);
  spec.validate();
  Model model(spec);
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(weights, ec), weights.string() << ": no such file (the model's weights)");
  torch::nn::Sequential& net = ModelAccess::network(model);
  std::vector<std::vector<std::int64_t>> expected;  // LibTorch's load takes whatever shapes the archive holds
  for (const torch::Tensor& t : net->parameters()) expected.push_back(t.sizes().vec());
  for (const torch::Tensor& t : net->buffers()) expected.push_back(t.sizes().vec());
  try {
    torch::serialize::InputArchive archive;
    archive.load_from(weights.string());
    net->load(archive);
  } catch (const c10::Error& e) {
    const std::string what = e.what_without_backtrace();
    PIXELCLOTH_FAIL(weights.string() << ": not the weights of a " << architectureName(spec.architecture)
                                     << " network of width " << spec.width
                                     << " (truncated, or from another model): " << what.substr(0, what.find('\n')));
  }
  std::vector<std::vector<std::int64_t>> found;
  for (const torch::Tensor& t : net->parameters()) found.push_back(t.sizes().vec());
  for (const torch::Tensor& t : net->buffers()) found.push_back(t.sizes().vec());
  PIXELCLOTH_CHECK(found == expected, weights.string() << ": its tensors do not have the shapes of a "
                                                       << architectureName(spec.architecture) << " network of width "
                                                       << spec.width << " (" << sidecarPath.string() << ")");
  return model;
}

Eigen::MatrixXf predictOffsets(const Model& model, const fs::path& datasetFolder, const Eigen::MatrixXf& poses) {
  const data::DatasetInfo info = data::readDatasetInfo(datasetFolder);
  const garment::Garment garment = data::datasetGarment(info);
  const ImageCodec codec(garment);
  PIXELCLOTH_CHECK(model.spec().outputShape() == codec.shape(),
                   "predict: the model's images do not fit the " << garment.name << " of " << datasetFolder.string());
  const Eigen::MatrixXf images = model.forward(poses);
  const auto shape = codec.shape();
  Eigen::MatrixXf out(poses.rows(), 3 * garment.mesh.numVertices());
  for (int r = 0; r < poses.rows(); ++r) {
    const Eigen::RowVectorXf row = images.row(r);
    const torch::Tensor image = toTensor(row).reshape(shape);
    const Eigen::MatrixXf offsets = codec.offsets(image);
    for (int v = 0; v < offsets.rows(); ++v) out.block<1, 3>(r, 3 * v) = offsets.row(v);
  }
  return out;
}

}  // namespace pixelcloth::learn
