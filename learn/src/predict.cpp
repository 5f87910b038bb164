#include "pixelcloth/learn/predict.h"

#include <torch/torch.h>

#include <algorithm>

#include "checkpoint.h"
#include "model_impl.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/patches/patch.h"
#include "target.h"
#include "tensor.h"

namespace pixelcloth::learn {

namespace fs = std::filesystem;

namespace {

struct LoadedNetwork {
  int patch = -1;
  nlohmann::json sidecar;
  Model model;
  std::unique_ptr<Target> target;
};

/// The settings every network of one model folder must share.
nlohmann::json sharedPart(nlohmann::json sidecar) {
  for (const char* key : {"patch", "epoch", "train_error_cm", "regularisation_error_cm"}) sidecar.erase(key);
  return sidecar;
}

/// Every network folder of a model folder, with its patch id (-1 for a single network), by patch.
std::vector<std::pair<int, fs::path>> networkFolders(const fs::path& folder) {
  std::vector<std::pair<int, fs::path>> found;
  std::error_code ec;
  if (fs::exists(folder / "model.json", ec)) return {{-1, folder}};
  PIXELCLOTH_CHECK(fs::is_directory(folder, ec), folder.string() << ": no such model folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name.rfind("patch_", 0) == 0 && fs::exists(entry.path() / "model.json"))
      found.push_back({std::atoi(name.c_str() + 6), entry.path()});
  }
  std::sort(found.begin(), found.end());
  PIXELCLOTH_CHECK(!found.empty(), folder.string() << ": no model.json, and no patch_NN/model.json (not a model "
                                                      "folder from pixelcloth train)");
  return found;
}

}  // namespace

fs::path trainingDatasetOf(const fs::path& modelFolder) {
  const fs::path sidecar = networkFolders(modelFolder).front().second / "model.json";
  return core::requireValue<std::string>(core::readJson(sidecar), "dataset", sidecar.string());
}

struct TrainedModel::Impl {
  fs::path folder;
  std::vector<LoadedNetwork> networks;
  Engine engine = Engine::OneDnn;
  std::unique_ptr<CompiledNetworks> compiled;  ///< the oneDNN engine's networks
};

TrainedModel::TrainedModel(const fs::path& folder, const garment::Garment& garment, Engine engine, int threads)
    : impl_(std::make_unique<Impl>()) {
  impl_->folder = folder;
  impl_->engine = engine;
  const std::vector<std::pair<int, fs::path>> found = networkFolders(folder);
  std::vector<patches::Patch> patchList;
  for (const auto& [patchId, path] : found) {
    const fs::path sidecarPath = path / "model.json";
    const std::string context = sidecarPath.string();
    nlohmann::json sidecar = core::readJson(sidecarPath);
    const ModelSpec spec = specOfSidecar(sidecar, context);
    PIXELCLOTH_CHECK(core::requireValue<int>(sidecar, "vertices", context) == garment.mesh.numVertices() &&
                         core::requireValue<std::string>(sidecar, "garment", context) == garment.name,
                     context << ": a model of the " << sidecar.value("garment", "?") << " with "
                             << sidecar.value("vertices", 0) << " vertices, not of this " << garment.name << " with "
                             << garment.mesh.numVertices());
    const patches::Patch* patch = nullptr;
    if (spec.architecture == Architecture::Patch) {
      if (patchList.empty()) patchList = patches::garmentPatches(garment);
      const int id = core::requireValue<int>(sidecar, "patch", context);
      PIXELCLOTH_CHECK(id == patchId || patchId < 0, context << ": the model of patch " << id << " in a folder for patch "
                                                             << patchId);
      PIXELCLOTH_CHECK(id >= 0 && id < static_cast<int>(patchList.size()),
                       context << ": patch " << id << ", but the " << garment.name << " has " << patchList.size());
      patch = &patchList[id];
    }
    if (!impl_->networks.empty())
      PIXELCLOTH_CHECK(sharedPart(sidecar) == sharedPart(impl_->networks.front().sidecar),
                       context << ": trained with other settings than "
                               << (impl_->folder / patchFolderName(impl_->networks.front().patch) / "model.json").string()
                               << " (architecture, width, dataset, space or base differ)");
    LoadedNetwork network{patch ? patch->id : -1, sidecar, Model(spec), targetOf(spec.architecture, garment, patch)};
    network.target->to(ModelAccess::device(network.model));
    PIXELCLOTH_CHECK(summarize(spec).output == network.target->shape(),
                     context << ": its output does not fit the " << garment.name);
    loadWeights(ModelAccess::network(network.model), path / "model.tensors",
                std::string("a ") + architectureName(spec.architecture) + " network of width " +
                    std::to_string(spec.width) + " (" + context + ")");
    impl_->networks.push_back(std::move(network));
  }
  if (engine == Engine::OneDnn) {
    std::vector<const Model*> models;
    for (const LoadedNetwork& n : impl_->networks) models.push_back(&n.model);
    impl_->compiled = std::make_unique<CompiledNetworks>(models, threads);
  }
}

TrainedModel::~TrainedModel() = default;
TrainedModel::TrainedModel(TrainedModel&&) noexcept = default;

const fs::path& TrainedModel::folder() const { return impl_->folder; }
Engine TrainedModel::engine() const { return impl_->engine; }
const nlohmann::json& TrainedModel::sidecar() const { return impl_->networks.front().sidecar; }
Architecture TrainedModel::architecture() const { return impl_->networks.front().model.spec().architecture; }
OffsetSpace TrainedModel::space() const {
  const std::string context = (impl_->folder / "model.json").string();
  return offsetSpaceFromName(core::valueOr<std::string>(sidecar(), "space", "", context), context + ": space");
}
int TrainedModel::inputs() const { return impl_->networks.front().model.spec().inputs(); }
int TrainedModel::poseSize() const { return core::valueOr(sidecar(), "pose_size", 0, (impl_->folder / "model.json").string()); }
int TrainedModel::markers() const { return core::valueOr(sidecar(), "markers", 0, (impl_->folder / "model.json").string()); }
bool TrainedModel::residual() const { return sidecar().contains("residual") && !sidecar()["residual"].is_null(); }
fs::path TrainedModel::baseFolder() const {
  return residual() ? fs::path(core::valueOr<std::string>(sidecar()["residual"], "folder", "", (impl_->folder / "model.json").string() + ": residual"))
                    : fs::path();
}

std::vector<int> TrainedModel::patches() const {
  std::vector<int> ids;
  for (const LoadedNetwork& n : impl_->networks)
    if (n.patch >= 0) ids.push_back(n.patch);
  return ids;
}

void TrainedModel::checkDataset(const data::DatasetInfo& dataset) const {
  PIXELCLOTH_CHECK(dataset.settings.vertexCount == core::valueOr(sidecar(), "vertices", -1, (impl_->folder / "model.json").string()) &&
                       dataset.settings.poseSize == poseSize(),
                   dataset.folder.string() << " holds the " << dataset.settings.garment << " ("
                                           << dataset.settings.vertexCount << " vertices, poses of "
                                           << dataset.settings.poseSize << "); the model in "
                                           << impl_->folder.string() << " is for the " << core::valueOr<std::string>(sidecar(), "garment", "?", (impl_->folder / "model.json").string())
                                           << " (" << core::valueOr(sidecar(), "vertices", -1, (impl_->folder / "model.json").string()) << " vertices, poses of "
                                           << poseSize() << ")");
}

std::vector<NetworkPrediction> TrainedModel::predict(const Eigen::MatrixXf& inputs) const {
  PIXELCLOTH_CHECK(inputs.cols() == this->inputs() && inputs.rows() > 0,
                   "predict: " << inputs.rows() << " x " << inputs.cols() << " inputs, expected batch x "
                               << this->inputs() << " (pose " << poseSize() << " + 3 x " << markers() << " markers)");
  PIXELCLOTH_CHECK(inputs.allFinite(), "predict: the inputs are not all finite");
  torch::NoGradGuard noGrad;
  std::vector<NetworkPrediction> out;
  if (impl_->compiled) {
    std::vector<RowsF> outputs;
    impl_->compiled->forward(inputs, outputs);
    for (size_t k = 0; k < impl_->networks.size(); ++k) {
      const LoadedNetwork& n = impl_->networks[k];
      std::vector<std::int64_t> shape{inputs.rows()};
      for (std::int64_t d : n.target->shape()) shape.push_back(d);
      const torch::Tensor output = torch::from_blob(outputs[k].data(), shape, torch::kFloat32);
      const torch::Tensor values = n.target->decode(output.to(ModelAccess::device(n.model)));  // B x n x 3
      out.push_back({n.patch, n.target->vertices(), toEigen(values)});
    }
    return out;
  }
  const torch::Tensor x = toTensor(inputs);
  for (LoadedNetwork& n : impl_->networks) {
    torch::nn::Sequential& net = ModelAccess::network(n.model);
    net->eval();
    const torch::Tensor values = n.target->decode(net->forward(x.to(ModelAccess::device(n.model))));  // B x n x 3
    out.push_back({n.patch, n.target->vertices(), toEigen(values)});
  }
  return out;
}

}  // namespace pixelcloth::learn
