// Training a network on a dataset: batches made on a prefetch thread, the losses, Adam, model selection, checkpoints.
#include "pixelcloth/learn/train.h"

#include <omp.h>
#include <torch/torch.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

#include "checkpoint.h"
#include "losses.h"
#include "model_impl.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/cpu.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/patches/patch.h"
#include "target.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
using core::secondsSince;

/// One step's data: the inputs, the encoded targets, the target values at the covered vertices (for the train error)
/// and, for the geometric losses, their frames, base values and true positions.
struct Batch {
  std::vector<int> rows;
  torch::Tensor inputs, targets;           ///< B x inputs; B x target shape
  torch::Tensor values;                    ///< B x n x 3
  torch::Tensor origin, t, b, n, base, truth;  ///< B x n x 3 each (geometry only)

  void to(const torch::Device& device) {
    for (torch::Tensor* tensor : {&inputs, &targets, &values, &origin, &t, &b, &n, &base, &truth})
      if (tensor->defined()) *tensor = tensor->to(device);
  }
};

/// Rows of per-row #V x 3 matrices at the target's vertices, as B x n x 3.
torch::Tensor gather(const std::vector<Eigen::MatrixXf>& perRow, const std::vector<int>& rows,
                     const torch::Tensor& vertices) {
  std::vector<torch::Tensor> parts;
  for (int r : rows) parts.push_back(toTensor(perRow[r]).index_select(0, vertices));
  return torch::stack(parts);
}

torch::Tensor gatherFrames(const TrainingData& data, const std::vector<int>& rows, const torch::Tensor& vertices,
                           Eigen::MatrixX3d garment::EmbeddedFrames::*member) {
  std::vector<torch::Tensor> parts;
  for (int r : rows) parts.push_back(toTensor((data.frames[r].*member).cast<float>()).index_select(0, vertices));
  return torch::stack(parts);
}

Batch makeBatch(const TrainingData& data, const Target& target, const torch::Tensor& vertices, std::vector<int> rows,
                bool geometry) {
  Batch batch;
  Eigen::MatrixXf inputs(rows.size(), data.inputs.cols());
  std::vector<torch::Tensor> targets;
  for (size_t k = 0; k < rows.size(); ++k) {
    inputs.row(k) = data.inputs.row(rows[k]);
    targets.push_back(target.encode(data.values[rows[k]]));
  }
  batch.inputs = toTensor(inputs);
  batch.targets = torch::stack(targets);
  batch.values = gather(data.values, rows, vertices);
  if (geometry) {
    batch.origin = gatherFrames(data, rows, vertices, &garment::EmbeddedFrames::origin);
    batch.t = gatherFrames(data, rows, vertices, &garment::EmbeddedFrames::t);
    batch.b = gatherFrames(data, rows, vertices, &garment::EmbeddedFrames::b);
    batch.n = gatherFrames(data, rows, vertices, &garment::EmbeddedFrames::n);
    batch.truth = gather(data.truth, rows, vertices);
    batch.base = data.residual() ? gather(data.base, rows, vertices) : torch::zeros_like(batch.truth);
  }
  batch.rows = std::move(rows);
  return batch;
}

/// Makes an epoch's batches on a second thread, at most two ahead of the trainer, so rasterising the targets overlaps
/// the network's steps.
class Prefetcher {
 public:
  Prefetcher(const TrainingData& data, const Target& target, const torch::Tensor& vertices,
             const std::vector<int>& order, int batchSize, bool geometry) {
    worker_ = std::thread([=, &data, &target] {
      try {
        for (size_t first = 0; first < order.size(); first += batchSize) {
          const size_t count = std::min<size_t>(batchSize, order.size() - first);
          Batch batch = makeBatch(data, target, vertices,
                                  std::vector<int>(order.begin() + first, order.begin() + first + count), geometry);
          std::unique_lock<std::mutex> lock(mutex_);
          changed_.wait(lock, [&] { return queue_.size() < 2 || stop_; });
          if (stop_) return;
          queue_.push_back(std::move(batch));
          changed_.notify_all();
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex_);
      finished_ = true;
      changed_.notify_all();
    });
  }
  ~Prefetcher() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
      changed_.notify_all();
    }
    worker_.join();
  }
  /// The next batch (none at the end of the epoch); adds the time spent waiting to `waited`.
  std::optional<Batch> next(double& waited) {
    const auto start = Clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return !queue_.empty() || finished_; });
    waited += secondsSince(start);
    if (error_) std::rethrow_exception(error_);
    if (queue_.empty()) return std::nullopt;
    Batch batch = std::move(queue_.front());
    queue_.pop_front();
    changed_.notify_all();
    return batch;
  }

 private:
  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Batch> queue_;
  bool finished_ = false, stop_ = false;
  std::exception_ptr error_;
};

/// Positions of predicted values (B x n x 3) plus the batch's base, in the data's space.
torch::Tensor positionsOf(OffsetSpace space, const torch::Tensor& values, const Batch& batch) {
  const torch::Tensor full = values + batch.base;
  switch (space) {
    case OffsetSpace::Local: return positionsFromOffsets(full, batch.origin, batch.t, batch.b, batch.n);
    case OffsetSpace::Root: return batch.origin + full;
    case OffsetSpace::Positions: return full;
  }
  return full;
}

/// A decoder's target images shifted and scaled per channel (TargetScaling::PerChannel); identity when empty.
struct ChannelScaling {
  torch::Tensor mean, spread;  ///< C x 1 x 1 each

  bool active() const { return mean.defined(); }
  /// Target images (B x C x H x W) as the network learns them.
  torch::Tensor scaled(const torch::Tensor& images) const { return active() ? (images - mean) / spread : images; }
  /// Network outputs back in metres.
  torch::Tensor metres(const torch::Tensor& outputs) const { return active() ? outputs * spread + mean : outputs; }
  void to(const torch::Device& device) {
    if (active()) {
      mean = mean.to(device);
      spread = spread.to(device);
    }
  }
};

/// Mean and spread of each channel of the train split's target images over their masked pixels (spread at least
/// 0.1 mm, so a channel that hardly varies is not blown up).
ChannelScaling channelScalingOf(const TrainingData& data, const Target& target) {
  const std::int64_t channels = target.shape().front();
  torch::Tensor sum = torch::zeros({channels}, torch::kDouble), squares = torch::zeros({channels}, torch::kDouble),
                count = torch::zeros({channels}, torch::kDouble);
  const torch::Tensor mask = target.mask().to(torch::kCPU).to(torch::kDouble);
  for (int row : data.train) {
    const torch::Tensor image = target.encode(data.values[row]).to(torch::kDouble);
    const torch::Tensor weights = mask.expand_as(image);
    sum += (image * weights).sum({1, 2});
    squares += (image * image * weights).sum({1, 2});
    count += weights.sum({1, 2});
  }
  count.clamp_min_(1);
  const torch::Tensor mean = sum / count;
  const torch::Tensor spread = (squares / count - mean * mean).clamp_min(0).sqrt().clamp_min(1e-4);
  return {mean.to(torch::kFloat).view({channels, 1, 1}), spread.to(torch::kFloat).view({channels, 1, 1})};
}

/// Writes the network's weights with `scaling` folded into its last layer (a convolution: out x in x k x k weights,
/// out biases), so the file predicts metres; the network itself is left as it was.
void saveScaledWeights(torch::nn::Sequential& net, const ChannelScaling& scaling, const fs::path& path) {
  if (!scaling.active()) return saveWeights(net, path);
  torch::NoGradGuard noGrad;
  std::vector<torch::Tensor> parameters = net->parameters();
  torch::Tensor &weight = parameters[parameters.size() - 2], &bias = parameters.back();
  const torch::Tensor weight0 = weight.clone(), bias0 = bias.clone();
  weight.mul_(scaling.spread.view({-1, 1, 1, 1}));
  bias.mul_(scaling.spread.view({-1})).add_(scaling.mean.view({-1}));
  saveWeights(net, path);
  weight.copy_(weight0);
  bias.copy_(bias0);
}

/// Mean per-vertex distance (cm) between the network's values and the targets over `rows`, on the target's vertices
/// (frames are orthonormal, so in every space it is the position error); NaN for no rows.
double errorCm(torch::nn::Sequential& net, const ChannelScaling& scaling, const Target& target,
               const TrainingData& data, const std::vector<int>& rows, const torch::Tensor& vertices,
               const torch::Device& device) {
  if (rows.empty()) return std::numeric_limits<double>::quiet_NaN();
  torch::NoGradGuard noGrad;
  net->eval();
  double sum = 0;
  for (size_t first = 0; first < rows.size(); first += 16) {
    const std::vector<int> chunk(rows.begin() + first, rows.begin() + std::min(rows.size(), first + 16));
    Eigen::MatrixXf inputs(chunk.size(), data.inputs.cols());
    for (size_t k = 0; k < chunk.size(); ++k) inputs.row(k) = data.inputs.row(chunk[k]);
    const torch::Tensor predicted = target.decode(scaling.metres(net->forward(toTensor(inputs).to(device))));
    sum += (predicted - gather(data.values, chunk, vertices).to(device)).norm(2, 2).mean(1).sum().item<double>();
  }
  return 100 * sum / rows.size();
}

std::string csvOf(const std::vector<EpochRecord>& epochs) {
  std::ostringstream csv;
  csv << "epoch,loss,normal_loss,edge_loss,train_error_cm,regularisation_error_cm,seconds,data_wait_seconds\n";
  for (const EpochRecord& e : epochs)
    csv << e.epoch << ',' << e.loss << ',' << e.normalLoss << ',' << e.edgeLoss << ',' << e.trainErrorCm << ','
        << e.regularisationErrorCm << ',' << e.seconds << ',' << e.dataWaitSeconds << '\n';
  return csv.str();
}

nlohmann::json numberOrNull(double value) { return std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value); }

/// Everything that decides a network's weights: a checkpoint resumes only under the same signature.
nlohmann::json signatureOf(const nlohmann::json& sidecar, const TrainOptions& options, double normalWeight,
                           double edgeWeight) {
  nlohmann::json signature = sidecar;
  signature.erase("dataset");  // the folder may move; its manifest checksum stays
  signature["batch"] = options.batch;
  signature["learning_rate"] = options.learningRate;
  signature["seed"] = options.seed;
  signature["normal_weight"] = normalWeight;
  signature["edge_weight"] = edgeWeight;
  signature["target_scaling"] = targetScalingName(options.targetScaling);
  signature["schedule"] = scheduleName(options.schedule);
  if (options.schedule != Schedule::Constant) signature["epochs"] = options.epochs;  // the rates depend on the length
  return signature;
}

struct NetworkJob {
  int patch = -1;
  fs::path folder;
  std::unique_ptr<Target> target;
};

/// Trains one network into `job.folder`.
NetworkReport trainNetwork(const TrainingData& data, NetworkJob& job, ModelSpec spec, const TrainOptions& options,
                           double normalWeight, double edgeWeight, core::Progress* progress) {
  Model model(spec, options.seed);
  const torch::Device device = ModelAccess::device(model);
  job.target->to(device);
  const Target& target = *job.target;
  core::ensureOutputFolder(job.folder);
  const std::vector<int>& vertexList = target.vertices();
  const torch::Tensor vertices =
      torch::tensor(std::vector<std::int64_t>(vertexList.begin(), vertexList.end()), torch::kInt64);
  const bool geometry = normalWeight > 0 || edgeWeight > 0;

  if (spec.architecture == Architecture::FullyConnectedPca) {
    Eigen::MatrixXf rows(data.train.size(), 3 * data.garment.mesh.numVertices());
    for (size_t k = 0; k < data.train.size(); ++k) rows.row(k) = toEigen(target.encode(data.values[data.train[k]]).unsqueeze(0));
    const PcaBasis basis = fitPca(rows, spec.pcaComponents);
    model.setPcaBasis(basis.mean, basis.components);
  }
  torch::nn::Sequential& net = ModelAccess::network(model);
  {
    // The last layer starts at zero: an untrained model predicts zero offsets (the base, in residual mode), not the
    // random images of LibTorch's default initialisation, whose values are tens of centimetres.
    torch::NoGradGuard noGrad;
    std::vector<torch::Tensor> parameters = net->parameters();
    for (size_t k = parameters.size() >= 2 ? parameters.size() - 2 : 0; k < parameters.size(); ++k)
      parameters[k].zero_();
  }
  const bool decoder = spec.architecture == Architecture::Whole || spec.architecture == Architecture::Patch ||
                       spec.architecture == Architecture::Necktie;
  ChannelScaling scaling;
  if (decoder && options.targetScaling == TargetScaling::PerChannel) scaling = channelScalingOf(data, target);
  scaling.to(device);
  torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(options.learningRate));
  const torch::Tensor mask = target.mask().unsqueeze(0);  // already on the device

  nlohmann::json sidecar = modelSidecar(spec, data, job.patch, imageLossName(options.loss));
  sidecar["target_scaling"] = targetScalingName(scaling.active() ? options.targetScaling : TargetScaling::None);
  const nlohmann::json signature = signatureOf(sidecar, options, normalWeight, edgeWeight);
  NetworkReport report;
  report.patch = job.patch;
  report.folder = job.folder;
  const fs::path checkpoint = job.folder / "checkpoint.tensors";
  if (fs::exists(checkpoint)) {
    loadCheckpoint(checkpoint, signature, net, adam, report);
    report.resumedAt = static_cast<int>(report.epochs.size());
  }
  std::mt19937_64 shuffle(options.seed);
  auto shuffled = [&] {
    std::vector<int> order = data.train;
    for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[shuffle() % i]);
    return order;
  };
  for (int e = 0; e < report.resumedAt; ++e) shuffled();  // the same orders as an uninterrupted run

  const bool hasRegularisation = !data.regularisation.empty();
  const std::int64_t stepsPerEpoch = (static_cast<std::int64_t>(data.train.size()) + options.batch - 1) / options.batch;
  auto setRate = [&](std::int64_t step) {
    const double rate = scheduledRate(options.schedule, options.learningRate, step, stepsPerEpoch * options.epochs);
    for (torch::optim::OptimizerParamGroup& group : adam.param_groups())
      static_cast<torch::optim::AdamOptions&>(group.options()).lr(rate);
  };
  for (int epoch = report.resumedAt + 1; epoch <= options.epochs; ++epoch) {
    if (options.patience > 0 && hasRegularisation && epoch - 1 - report.bestEpoch >= options.patience) {
      report.stoppedEarly = true;  // checked first, so a resumed run that had stopped stops again
      break;
    }
    const auto start = Clock::now();
    EpochRecord record;
    record.epoch = epoch;
    net->train();
    int steps = 0;
    double trainErrorSum = 0;
    Prefetcher prefetch(data, target, vertices, shuffled(), options.batch, geometry);
    while (std::optional<Batch> batch = prefetch.next(record.dataWaitSeconds)) {
      batch->to(device);
      const torch::Tensor output = net->forward(batch->inputs);
      torch::Tensor value = maskedImageLoss(output, scaling.scaled(batch->targets), mask, options.loss);
      record.loss += value.item<double>();
      // The values at the vertices: the train error from the step's own forward pass, and the geometric losses.
      const torch::Tensor decoded = target.decode(scaling.metres(output));
      trainErrorSum += (decoded.detach() - batch->values).norm(2, 2).mean(1).sum().item<double>();
      if (geometry) {
        const torch::Tensor predicted = positionsOf(data.space, decoded, *batch);
        if (normalWeight > 0) {
          const torch::Tensor normal = normalLoss(predicted, batch->truth, target.faces());
          record.normalLoss += normal.item<double>();
          value = value + normalWeight * normal;
        }
        if (edgeWeight > 0) {
          const torch::Tensor edge = edgeLengthLoss(predicted, batch->truth, target.edges());
          record.edgeLoss += edge.item<double>();
          value = value + edgeWeight * edge;
        }
      }
      setRate((epoch - 1) * stepsPerEpoch + steps);
      adam.zero_grad();
      value.backward();
      adam.step();
      ++steps;
    }
    record.loss /= steps;
    record.normalLoss /= steps;
    record.edgeLoss /= steps;
    // The train error is the mean over the epoch's steps as they were taken (training mode, the weights moving):
    // another forward pass over the whole train split would cost about a quarter of the epoch again.
    record.trainErrorCm = 100 * trainErrorSum / static_cast<double>(data.train.size());
    record.regularisationErrorCm = errorCm(net, scaling, target, data, data.regularisation, vertices, device);
    record.seconds = secondsSince(start);
    report.epochs.push_back(record);
    // Model selection on the regularisation split (the test split is only for reporting); without one, the last.
    if (report.bestEpoch == 0 || !hasRegularisation || record.regularisationErrorCm < report.bestErrorCm) {
      report.bestEpoch = epoch;
      report.bestErrorCm = hasRegularisation ? record.regularisationErrorCm : record.trainErrorCm;
      saveScaledWeights(net, scaling, job.folder / "model.tensors");
      sidecar["epoch"] = epoch;
      sidecar["train_error_cm"] = record.trainErrorCm;
      sidecar["regularisation_error_cm"] = numberOrNull(record.regularisationErrorCm);
      core::writeJson(job.folder / "model.json", sidecar);
    }
    core::writeTextAtomically(job.folder / "log.csv", csvOf(report.epochs));
    saveCheckpoint(checkpoint, signature, net, adam, report);  // last: a kill before it redoes this epoch
    if (progress) progress->advance();
  }
  return report;
}

}  // namespace

namespace {
const core::EnumNames<ImageLoss, 2> kImageLosses{"loss", {{{ImageLoss::L1, "l1"}, {ImageLoss::L2, "l2"}}}};
}  // namespace

const char* imageLossName(ImageLoss loss) { return kImageLosses.name(loss); }

const core::EnumNames<Schedule, 3> kSchedules{
    "schedule", {{{Schedule::Constant, "constant"}, {Schedule::Cosine, "cosine"}, {Schedule::Step, "step"}}}};
const char* scheduleName(Schedule schedule) { return kSchedules.name(schedule); }
Schedule scheduleFromName(const std::string& name, const std::string& context) {
  return kSchedules.fromName(name, context);
}

double scheduledRate(Schedule schedule, double rate, std::int64_t step, std::int64_t steps) {
  const double progress = steps > 0 ? static_cast<double>(step) / static_cast<double>(steps) : 0.0;
  switch (schedule) {
    case Schedule::Constant:
      return rate;
    case Schedule::Cosine:
      return 0.5 * rate * (1 + std::cos(M_PI * std::min(1.0, progress)));
    case Schedule::Step:
      return progress < 0.5 ? rate : progress < 0.75 ? 0.1 * rate : 0.01 * rate;
  }
  return rate;
}

const core::EnumNames<TargetScaling, 2> kTargetScalings{
    "target scaling", {{{TargetScaling::None, "none"}, {TargetScaling::PerChannel, "per-channel"}}}};
const char* targetScalingName(TargetScaling scaling) { return kTargetScalings.name(scaling); }
TargetScaling targetScalingFromName(const std::string& name, const std::string& context) {
  return kTargetScalings.fromName(name, context);
}
ImageLoss imageLossFromName(const std::string& name, const std::string& context) {
  return kImageLosses.fromName(name, context);
}

void TrainOptions::validate() const {
  ModelSpec spec = model;  // train() sets the baselines' output size from the dataset; check the rest now
  if (spec.outputValues == 0) spec.outputValues = std::max(3, spec.pcaComponents);
  spec.validate();
  PIXELCLOTH_CHECK(epochs >= 1 && epochs <= 100000, "train: " << epochs << " epochs, expected 1 to 100000");
  PIXELCLOTH_CHECK(batch >= 1 && batch <= 4096, "train: batch " << batch << ", expected 1 to 4096");
  PIXELCLOTH_CHECK(std::isfinite(learningRate) && learningRate > 0,
                   "train: learning rate " << learningRate << ", expected > 0");
  PIXELCLOTH_CHECK(std::isfinite(normalWeight) && std::isfinite(edgeWeight),
                   "train: the normal and edge weights must be finite");
  PIXELCLOTH_CHECK(patience >= 0, "train: patience " << patience << ", expected 0 (off) or more epochs");
  PIXELCLOTH_CHECK(trainSamples >= 0, "train: " << trainSamples << " train samples, expected 0 (all) or more");
  PIXELCLOTH_CHECK(threads >= 0 && threads <= 1024, "train: " << threads << " threads, expected 0 to 1024");
  PIXELCLOTH_CHECK(networksAtOnce >= 0 && networksAtOnce <= 1024,
                   "train: " << networksAtOnce << " networks at once, expected 0 to 1024");
  PIXELCLOTH_CHECK(patches.empty() || model.architecture == Architecture::Patch,
                   "train: --patches is for the patch model, not " << architectureName(model.architecture));
  PIXELCLOTH_CHECK(space != OffsetSpace::Positions || model.architecture == Architecture::FullyConnected ||
                       model.architecture == Architecture::FullyConnectedPca,
                   "train: positions are the baselines' space (fc, fc-pca); the decoders predict local or root offsets");
}

void checkModelFolder(const fs::path& out, const nlohmann::json& settings, bool patchModel, const std::string& what) {
  if (!patchModel) return core::checkRunFolder(out, {"model.json", settings, what});
  core::checkRunFolder(out, {core::kPatchModelFile, {}, what});
  std::error_code ec;
  if (!fs::is_directory(out, ec)) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(out, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory(ec) && name.rfind("patch_", 0) == 0)
      core::checkRunFolder(entry.path(), {"model.json", settings, what + "'s decoder " + name});
  }
}

TrainReport train(const data::DatasetFolder& dataset, const fs::path& out, const TrainOptions& options) {
  const fs::path& datasetFolder = dataset.path;
  options.validate();
  const auto start = Clock::now();
  const ThreadScope cores(options.threads);
  keepFreedMemory();
  const data::DatasetInfo info = data::readDatasetInfo(dataset);
  const garment::Garment garment = data::datasetGarment(info);
  const garment::GarmentTraits& traits = garment.traits;
  if (options.model.architecture == Architecture::Whole || options.model.architecture == Architecture::Necktie) {
    // A whole-garment decoder draws the garment's cloth image: every layout's three channels at its image size.
    const std::vector<std::int64_t> shape = options.model.outputShape();
    const std::vector<std::int64_t> image = {3 * garment.numLayouts(), traits.imageHeight, traits.imageWidth};
    PIXELCLOTH_CHECK(shape == image,
                     "train: the " << architectureName(options.model.architecture) << " model does not fit "
                                   << datasetFolder.string() << ": it draws " << shape[0] << " x " << shape[1] << " x "
                                   << shape[2] << " cloth images, the dataset's garment (" << garment.name << ", "
                                   << garment.numLayouts() << " layouts) needs " << image[0] << " x " << image[1]
                                   << " x " << image[2] << " (--model whole draws two layouts at 256 x 256, --model "
                                   << "necktie one at 256 x 64; patch, fc and fc-pca fit any garment)");
  }
  const OffsetSpace space = options.space.value_or(traits.rootFrameOffsets ? OffsetSpace::Root : OffsetSpace::Local);
  const double normalWeight = options.normalWeight >= 0 ? options.normalWeight : traits.normalLossWeight;
  const double edgeWeight = options.edgeWeight >= 0 ? options.edgeWeight : traits.edgeLossWeight;
  TrainingData data = loadTrainingData(dataset, space, options.residual);
  PIXELCLOTH_CHECK(!data.train.empty(), "train: " << datasetFolder.string() << " has no training samples");
  if (options.trainSamples > 0) {
    PIXELCLOTH_CHECK(options.trainSamples <= static_cast<int>(data.train.size()),
                     "train --train-samples " << options.trainSamples << ": " << datasetFolder.string() << " has "
                                              << data.train.size() << " samples in its train split");
    data.train.resize(options.trainSamples);
  }

  ModelSpec spec = options.model;
  spec.inputSize = static_cast<int>(data.inputs.cols());
  if (spec.architecture == Architecture::FullyConnected || spec.architecture == Architecture::FullyConnectedPca)
    spec.outputValues = 3 * data.garment.mesh.numVertices();
  if (spec.architecture == Architecture::FullyConnectedPca &&
      spec.pcaComponents > static_cast<int>(data.train.size())) {
    PIXELCLOTH_WARN("train: " << spec.pcaComponents << " PCA components asked, but the train split has "
                              << data.train.size() << " samples; using " << data.train.size());
    spec.pcaComponents = static_cast<int>(data.train.size());
  }
  spec.validate();

  std::vector<NetworkJob> jobs;
  if (spec.architecture == Architecture::Patch) {
    const std::vector<patches::Patch> patchList = patches::garmentPatches(data.garment);
    std::vector<int> ids = options.patches;
    if (ids.empty())
      for (const patches::Patch& p : patchList) ids.push_back(p.id);
    for (int id : ids) {
      PIXELCLOTH_CHECK(id >= 0 && id < static_cast<int>(patchList.size()),
                       "train --patches: no patch " << id << "; the " << data.garment.name << " has patches 0 to "
                                                    << patchList.size() - 1);
      jobs.push_back({id, out / patchFolderName(id), patchCropTarget(data.garment, patchList[id])});
    }
  } else {
    jobs.push_back({-1, out, targetOf(spec.architecture, data.garment, nullptr)});
  }
  for (const NetworkJob& job : jobs)
    PIXELCLOTH_CHECK(summarize(spec).output == job.target->shape(),
                     "train: the " << architectureName(spec.architecture) << " model predicts "
                                   << core::npyShapeString(summarize(spec).output) << " but the "
                                   << data.garment.name << "'s " << (job.patch >= 0 ? "patch crops" : "images")
                                   << " are " << core::npyShapeString(job.target->shape()));
  {
    // What decides the folder's contents; loss, epochs and rates may change between runs (checkpoints resume only
    // under their own, stricter signature).
    const nlohmann::json sidecar = modelSidecar(spec, data, -1, imageLossName(options.loss));
    nlohmann::json settings;
    for (const char* key : {"architecture", "width", "min_channels", "pca_components", "garment", "vertices",
                            "pose_size", "markers", "space", "residual"})
      settings[key] = sidecar[key];
    checkModelFolder(out, settings, spec.architecture == Architecture::Patch,
                     std::string("the ") + architectureName(spec.architecture) + " model");
  }
  core::ensureOutputFolder(out);

  TrainReport report;
  std::unique_ptr<core::Progress> progress;
  progress = std::make_unique<core::Progress>("train " + std::string(architectureName(spec.architecture)),
                                              static_cast<std::int64_t>(jobs.size()) * options.epochs);
  auto trainJob = [&](size_t k) {
    NetworkReport network = trainNetwork(data, jobs[k], spec, options, normalWeight, edgeWeight, progress.get());
    if (progress && network.resumedAt > 0) progress->advance(std::min(network.resumedAt, options.epochs));
    if (progress && network.stoppedEarly) progress->advance(options.epochs - static_cast<int>(network.epochs.size()));
    return network;
  };
  const int threads = torch::get_num_threads();
  const int atOnce = static_cast<int>(std::min<size_t>(
      jobs.size(), options.networksAtOnce > 0 ? options.networksAtOnce : std::max(1, threads)));
  if (atOnce <= 1) {
    for (size_t k = 0; k < jobs.size(); ++k) report.networks.push_back(trainJob(k));
  } else {
    // Small networks keep one core busier than a share of two: each worker trains networks one thread each, taking
    // the next job when it is done.
    report.networks.resize(jobs.size());
    std::atomic<size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    std::vector<std::thread> workers;
    for (int w = 0; w < atOnce; ++w)
      workers.emplace_back([&, w] {
        torch::get_num_threads();  // LibTorch sets up this thread's OpenMP threads on first use; then one per worker
        omp_set_num_threads(std::max(1, threads / atOnce + (w < threads % atOnce ? 1 : 0)));
        for (size_t k = next++; k < jobs.size(); k = next++) {
          try {
            report.networks[k] = trainJob(k);
          } catch (...) {
            const std::lock_guard<std::mutex> lock(failureMutex);
            if (!failure) failure = std::current_exception();
            next = jobs.size();
          }
        }
      });
    for (std::thread& t : workers) t.join();
    if (failure) std::rethrow_exception(failure);
  }
  if (progress) progress->finish();
  report.seconds = secondsSince(start);
  return report;
}

}  // namespace pixelcloth::learn
