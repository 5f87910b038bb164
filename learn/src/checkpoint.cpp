#include "checkpoint.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "model_impl.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/learn/weights_file.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace fs = std::filesystem;

namespace {

constexpr int kRecordFields = 8;

}  // namespace

std::string patchFolderName(int patch) {
  char name[32];
  std::snprintf(name, sizeof(name), "patch_%02d", patch);
  return name;
}

nlohmann::json modelSidecar(const ModelSpec& spec, const TrainingData& data, int patch, const std::string& loss) {
  return {{"format", "pixelcloth.model"},
          {"version", 1},
          {"architecture", architectureName(spec.architecture)},
          {"width", spec.width},
          {"inputs", spec.inputs()},
          {"output", summarize(spec).output},
          {"values", spec.outputValues},
          {"pca_components", spec.pcaComponents},
          {"min_channels", spec.minChannels},
          {"garment", data.garment.name},
          {"vertices", data.garment.mesh.numVertices()},
          {"pose_size", data.poseSize},
          {"markers", data.markers},
          {"space", offsetSpaceName(data.space)},
          {"loss", loss},
          {"dataset", fs::absolute(data.folder).lexically_normal().string()},
          {"dataset_manifest_crc32", data.manifestCrc},
          {"train_samples", data.train.size()},
          {"residual", data.residual()
                           ? nlohmann::json{{"folder", fs::absolute(data.baseFolder).lexically_normal().string()},
                                            {"manifest_crc32", data.baseCrc}}
                           : nlohmann::json(nullptr)},
          {"patch", patch >= 0 ? nlohmann::json(patch) : nlohmann::json(nullptr)}};
}

ModelSpec specOfSidecar(const nlohmann::json& json, const std::string& context) {
  // Not json.value(), which throws nlohmann's type_error for a "format" that is not a string (fuzzing found it).
  const std::string format = json.is_object() && json.contains("format") && json["format"].is_string()
                                 ? json["format"].get<std::string>()
                                 : json.is_object() && json.contains("format") ? json["format"].dump() : "";
  PIXELCLOTH_CHECK(json.is_object() && format == "pixelcloth.model",
                   context << ": not a pixelcloth model (format '" << format << "')");
  ModelSpec spec;
  spec.architecture =
      architectureFromName(core::requireValue<std::string>(json, "architecture", context), context + ": architecture");
  spec.width = core::requireValue<double>(json, "width", context);
  spec.inputSize = core::requireValue<int>(json, "inputs", context);
  spec.outputValues = core::requireValue<int>(json, "values", context);
  spec.pcaComponents = core::requireValue<int>(json, "pca_components", context);
  // Models written before the channel floor have no "min_channels": their layers are the plain multiplier's.
  spec.minChannels = core::valueOr(json, "min_channels", 0, context);
  try {
    spec.validate();
  } catch (const core::InputError& e) {
    PIXELCLOTH_FAIL(context << ": " << e.what());  // "model: width 0, expected (0, 4]" names no file
  }
  return spec;
}

void saveWeights(const torch::nn::Sequential& net, const fs::path& path) { saveModuleWeights(*net, path); }

void loadWeights(torch::nn::Sequential& net, const fs::path& path, const std::string& what) {
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), path.string() << ": no such file (the weights of " << what << ")");
  loadModuleWeights(*net, path, what);
}

// checkpoint.tensors: the network's arrays under "model/", Adam's moments under "adam/<i>/" for the i-th parameter
// (counting from 0, in net->parameters() order) that has taken a step, the epoch records and the best epoch; the
// signature and Adam's step counts in the header's meta.
void saveCheckpoint(const fs::path& path, const nlohmann::json& signature, const torch::nn::Sequential& net,
                    torch::optim::Adam& adam, const NetworkReport& report) {
  core::TensorFile file;
  file.kind = "checkpoint";
  appendModuleArrays(*net, file, "model/");
  nlohmann::json steps = nlohmann::json::array();
  const std::vector<torch::Tensor> parameters = net->parameters();
  for (size_t i = 0; i < parameters.size(); ++i) {
    const auto found = adam.state().find(c10::guts::to_string(parameters[i].unsafeGetTensorImpl()));
    if (found == adam.state().end()) {
      steps.push_back(0);
      continue;
    }
    const auto& state = static_cast<const torch::optim::AdamParamState&>(*found->second);
    steps.push_back(state.step());
    const std::string prefix = "adam/" + std::to_string(i) + "/";
    file.arrays.emplace_back(prefix + "exp_avg", arrayOfTensor(state.exp_avg(), prefix + "exp_avg"));
    file.arrays.emplace_back(prefix + "exp_avg_sq", arrayOfTensor(state.exp_avg_sq(), prefix + "exp_avg_sq"));
  }
  std::vector<double> records;
  for (const EpochRecord& e : report.epochs)
    records.insert(records.end(), {double(e.epoch), e.loss, e.normalLoss, e.edgeLoss, e.trainErrorCm,
                                   e.regularisationErrorCm, e.seconds, e.dataWaitSeconds});
  file.arrays.emplace_back(
      "records", core::NpyArray::from(records, {static_cast<std::int64_t>(report.epochs.size()), kRecordFields}));
  file.arrays.emplace_back("best", core::NpyArray::from(std::vector<double>{double(report.bestEpoch), report.bestErrorCm}, {2}));
  file.meta = {{"signature", signature}, {"adam_steps", steps}};
  core::writeTensorFile(path, file);
}

void loadCheckpoint(const fs::path& path, const nlohmann::json& signature, torch::nn::Sequential& net,
                    torch::optim::Adam& adam, NetworkReport& report) {
  const std::string name = path.string();
  core::TensorFile file;
  try {
    file = core::readTensorFile(path, "checkpoint");
  } catch (const core::InputError& e) {
    PIXELCLOTH_FAIL(e.what() << "; delete it to start the run afresh");
  }
  const nlohmann::json previous = file.meta.contains("signature") ? file.meta["signature"] : nlohmann::json();
  if (previous != signature) {
    // Every setting that differs, in either direction.
    std::set<std::string> keys;
    for (const nlohmann::json* side : {&previous, &signature})
      if (side->is_object())
        for (const auto& item : side->items()) keys.insert(item.key());
    auto valueIn = [](const nlohmann::json& side, const std::string& key) {
      return side.is_object() && side.contains(key) ? side[key].dump() : std::string("none");
    };
    std::ostringstream differences;
    for (const std::string& key : keys)
      if (valueIn(previous, key) != valueIn(signature, key))
        differences << (differences.tellp() > 0 ? "; " : "") << key << ": " << valueIn(previous, key) << " there, "
                    << valueIn(signature, key) << " now";
    PIXELCLOTH_FAIL(name << ": holds a run with other settings (" << differences.str()
                         << "); use another --out, or delete the folder to start afresh");
  }
  const std::string what = "this run's network";
  loadModuleArrays(*net, file, path, what, "model/");

  const std::vector<torch::Tensor> parameters = net->parameters();
  const auto steps = core::requireValue<std::vector<std::int64_t>>(file.meta, "adam_steps", name + ": meta");
  PIXELCLOTH_CHECK(steps.size() == parameters.size(), name << ": Adam steps for " << steps.size()
                                                           << " parameters, the network has " << parameters.size());
  adam.state().clear();
  for (size_t i = 0; i < parameters.size(); ++i) {
    PIXELCLOTH_CHECK(steps[i] >= 0, name << ": Adam step " << steps[i] << " for parameter " << i);
    if (steps[i] == 0) continue;
    const std::string prefix = "adam/" + std::to_string(i) + "/";
    auto state = std::make_unique<torch::optim::AdamParamState>();
    state->step(steps[i]);
    torch::Tensor average = torch::zeros_like(parameters[i]), squares = torch::zeros_like(parameters[i]);
    for (auto [key, tensor] : {std::pair{"exp_avg", &average}, std::pair{"exp_avg_sq", &squares}}) {
      const core::NpyArray* array = file.find(prefix + key);
      PIXELCLOTH_CHECK(array, name << ": has no array '" << prefix << key << "' (Adam's state of parameter " << i << ")");
      copyArrayInto(*tensor, *array, prefix + key, path, what);
    }
    state->exp_avg(average);
    state->exp_avg_sq(squares);
    adam.state()[c10::guts::to_string(parameters[i].unsafeGetTensorImpl())] = std::move(state);
  }

  const core::NpyArray* records = file.find("records");
  const core::NpyArray* best = file.find("best");
  PIXELCLOTH_CHECK(records && records->dtype == "<f8" && records->shape.size() == 2 &&
                       records->shape[1] == kRecordFields && best && best->dtype == "<f8" && best->size() == 2,
                   name << ": its epoch records are missing or not " << kRecordFields << " float64 columns");
  // The epochs are numbered 1, 2, ... in order, and the best is one of them (or 0, none yet): checked before they are
  // converted to int (fuzzing found an epoch of 4e180, undefined behaviour as an int).
  report.epochs.clear();
  const double* f = records->data<double>();
  for (std::int64_t i = 0; i < records->shape[0]; ++i, f += kRecordFields) {
    PIXELCLOTH_CHECK(f[0] == double(i + 1), name << ": epoch record " << i + 1 << " is for epoch " << f[0]
                                                 << ", expected " << i + 1 << " (the records are damaged)");
    report.epochs.push_back({int(f[0]), f[1], f[2], f[3], f[4], f[5], f[6], f[7]});
  }
  const double bestEpoch = best->data<double>()[0];
  PIXELCLOTH_CHECK(bestEpoch >= 0 && bestEpoch <= double(records->shape[0]) && bestEpoch == std::floor(bestEpoch),
                   name << ": best epoch " << bestEpoch << ", expected one of the " << records->shape[0]
                        << " recorded (or 0)");
  report.bestEpoch = int(bestEpoch);
  report.bestErrorCm = best->data<double>()[1];
}

}  // namespace pixelcloth::learn
