#include "checkpoint.h"

#include <cstdio>

#include "model_impl.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"

namespace pixelcloth::learn {

namespace fs = std::filesystem;

namespace {

std::vector<std::vector<std::int64_t>> shapesOf(const torch::nn::Sequential& net) {
  std::vector<std::vector<std::int64_t>> shapes;
  for (const torch::Tensor& t : net->parameters()) shapes.push_back(t.sizes().vec());
  for (const torch::Tensor& t : net->buffers()) shapes.push_back(t.sizes().vec());
  return shapes;
}

// LibTorch's loaders throw c10::Error, and torch::jit::ErrorReport (a std::exception) when the pickle names a type
// it cannot parse: both are a damaged file (fuzzing found the second).
std::string firstLine(const std::exception& e) {
  const auto* error = dynamic_cast<const c10::Error*>(&e);
  const std::string what = error ? error->what_without_backtrace() : e.what();
  const size_t start = what.find_first_not_of(" \n");
  if (start == std::string::npos) return "no reason given";
  return what.substr(start, what.find('\n', start) - start);
}

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
          {"garment", data.garment.name},
          {"vertices", data.garment.mesh.numVertices()},
          {"pose_size", data.poseSize},
          {"markers", data.markers},
          {"space", offsetSpaceName(data.space)},
          {"loss", loss},
          {"dataset", fs::absolute(data.folder).lexically_normal().string()},
          {"dataset_manifest_crc32", data.manifestCrc},
          {"residual", data.residual() ? nlohmann::json{{"folder", fs::absolute(data.baseFolder).lexically_normal().string()},
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
  spec.validate();
  return spec;
}

void saveWeights(const torch::nn::Sequential& net, const fs::path& path) {
  torch::serialize::OutputArchive archive;
  net->save(archive);
  core::writeAtomically(path, [&](const fs::path& temporary) { archive.save_to(temporary.string()); });
}

void loadWeights(torch::nn::Sequential& net, const fs::path& path, const std::string& what) {
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), path.string() << ": no such file (the weights of " << what << ")");
  const auto expected = shapesOf(net);
  try {
    torch::serialize::InputArchive archive;
    archive.load_from(path.string());
    net->load(archive);
  } catch (const std::exception& e) {
    PIXELCLOTH_FAIL(path.string() << ": not the weights of " << what << " (truncated, or from another model): "
                                  << firstLine(e));
  }
  PIXELCLOTH_CHECK(shapesOf(net) == expected,
                   path.string() << ": its tensors do not have the shapes of " << what << " (another architecture or width)");
}

void saveCheckpoint(const fs::path& path, const nlohmann::json& signature, const torch::nn::Sequential& net,
                    torch::optim::Adam& adam, const NetworkReport& report) {
  torch::serialize::OutputArchive archive, model, optimizer;
  net->save(model);
  adam.save(optimizer);
  archive.write("model", model);
  archive.write("optimizer", optimizer);
  archive.write("signature", c10::IValue(signature.dump()));
  torch::Tensor records = torch::zeros({static_cast<std::int64_t>(report.epochs.size()), kRecordFields}, torch::kFloat64);
  for (size_t i = 0; i < report.epochs.size(); ++i) {
    const EpochRecord& e = report.epochs[i];
    const double fields[kRecordFields] = {double(e.epoch),      e.loss,   e.normalLoss, e.edgeLoss, e.trainErrorCm,
                                          e.regularisationErrorCm, e.seconds, e.dataWaitSeconds};
    for (int k = 0; k < kRecordFields; ++k) records[i][k] = fields[k];
  }
  archive.write("records", records);
  archive.write("best", torch::tensor({double(report.bestEpoch), report.bestErrorCm}, torch::kFloat64));
  core::writeAtomically(path, [&](const fs::path& temporary) { archive.save_to(temporary.string()); });
}

void loadCheckpoint(const fs::path& path, const nlohmann::json& signature, torch::nn::Sequential& net,
                    torch::optim::Adam& adam, NetworkReport& report) {
  const auto expected = shapesOf(net);
  torch::serialize::InputArchive archive, model, optimizer;
  c10::IValue stored;
  torch::Tensor records, best;
  try {
    archive.load_from(path.string());
    archive.read("signature", stored);
  } catch (const std::exception& e) {
    PIXELCLOTH_FAIL(path.string() << ": not a pixelcloth training checkpoint (truncated or damaged): " << firstLine(e)
                                  << "; delete it to start the run afresh");
  }
  PIXELCLOTH_CHECK(stored.isString(), path.string() << ": not a pixelcloth training checkpoint");
  const nlohmann::json previous = nlohmann::json::parse(stored.toStringRef(), nullptr, false);
  if (previous != signature) {
    std::string key = "?";
    for (const auto& [k, v] : signature.items())
      if (!previous.contains(k) || previous[k] != v) {
        key = k;
        break;
      }
    PIXELCLOTH_FAIL(path.string() << ": holds a run with other settings (" << key << ": "
                                  << (previous.is_object() && previous.contains(key) ? previous[key].dump() : "none")
                                  << " there, " << (signature.contains(key) ? signature[key].dump() : "none")
                                  << " now); use another --out, or delete the folder to start afresh");
  }
  try {
    archive.read("model", model);
    net->load(model);
    archive.read("optimizer", optimizer);
    adam.load(optimizer);
    archive.read("records", records);
    archive.read("best", best);
  } catch (const std::exception& e) {
    PIXELCLOTH_FAIL(path.string() << ": a damaged training checkpoint: " << firstLine(e));
  }
  // The records are read through data_ptr<double> and item<double>: a float32 or a 2-D "best" would have escaped as
  // LibTorch's c10::Error instead of naming the file.
  PIXELCLOTH_CHECK(shapesOf(net) == expected && records.dim() == 2 && records.size(1) == kRecordFields &&
                       records.scalar_type() == torch::kFloat64 && best.dim() == 1 && best.numel() == 2 &&
                       best.scalar_type() == torch::kFloat64,
                   path.string() << ": a training checkpoint whose tensors do not fit this model");
  report.epochs.clear();
  const torch::Tensor r = records.contiguous();
  for (std::int64_t i = 0; i < r.size(0); ++i) {
    const double* f = r[i].data_ptr<double>();
    report.epochs.push_back({int(f[0]), f[1], f[2], f[3], f[4], f[5], f[6], f[7]});
  }
  report.bestEpoch = int(best[0].item<double>());
  report.bestErrorCm = best[1].item<double>();
}

}  // namespace pixelcloth::learn
