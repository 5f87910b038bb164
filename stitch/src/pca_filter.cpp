#include "pixelcloth/stitch/pca_filter.h"

#include <algorithm>
#include <chrono>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::stitch {

namespace {

constexpr const char* kFormat = "pixelcloth.pca_filter";

/// A row vector of an Eigen column vector, for writeNpy's 2-D overload.
Eigen::MatrixXf row(const Eigen::VectorXf& v) { return v.transpose(); }

}  // namespace

PcaFilter PcaFilter::fit(const learn::TrainingData& data, int rank, learn::PcaMethod method) {
  const int V = data.garment.mesh.numVertices();
  const std::vector<int>& train = data.train;
  PIXELCLOTH_CHECK(!train.empty(), data.folder.string() << ": no train samples to fit a PCA filter on");
  const int most = static_cast<int>(std::min<long long>(train.size(), 3LL * V));
  if (rank == 0) rank = std::min(2048, most);
  PIXELCLOTH_CHECK(rank >= 1 && rank <= most, "pca filter: rank " << rank << " of " << train.size()
                                                                   << " train samples of " << 3 * V
                                                                   << " values, expected 1 to " << most);
  Eigen::MatrixXf rows(static_cast<Eigen::Index>(train.size()), 3 * V);
  for (size_t k = 0; k < train.size(); ++k) {
    Eigen::MatrixX3f values = data.values[train[k]];
    if (data.residual()) values += data.base[train[k]];
    // Vertex-major: the transpose of #V x 3 in column-major storage is v0 du dv dn, v1 ...
    const Eigen::MatrixXf t = values.transpose();
    rows.row(static_cast<Eigen::Index>(k)) = Eigen::Map<const Eigen::RowVectorXf>(t.data(), 3 * V);
  }
  const auto start = std::chrono::steady_clock::now();
  PcaFilter filter;
  filter.basis_ = learn::fitPca(rows, rank, method);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  filter.info_ = {{"format", kFormat},
                  {"version", 1},
                  {"garment", data.garment.name},
                  {"vertices", V},
                  {"space", learn::offsetSpaceName(data.space)},
                  {"rank", rank},
                  {"method", learn::pcaMethodName(method)},
                  {"seconds", seconds},
                  {"samples", train.size()},
                  {"dataset", data.folder.string()},
                  {"dataset_manifest_crc32", data.manifestCrc},
                  {"base", data.residual() ? nlohmann::json(data.baseFolder.string()) : nlohmann::json()}};
  PIXELCLOTH_INFO("PCA filter: rank " << rank << " of " << train.size() << " x " << 3 * V << " ("
                                      << learn::pcaMethodName(method) << ") in " << seconds << " s");
  return filter;
}

void PcaFilter::save(const std::filesystem::path& folder) const {
  core::ensureOutputFolder(folder);
  nlohmann::json info = info_;
  const std::pair<const char*, Eigen::MatrixXf> arrays[] = {
      {"mean.npy", row(basis_.mean)}, {"components.npy", basis_.components}, {"variance.npy", row(basis_.variance)}};
  for (const auto& [name, matrix] : arrays) {
    core::writeNpy(folder / name, matrix);
    info["files"][name] = data::fileCrc32(folder / name);
  }
  // pca.json last: a folder without it (a crash part-way) is not a filter.
  core::writeJson(folder / "pca.json", info);
}

PcaFilter PcaFilter::load(const std::filesystem::path& folder) {
  const std::filesystem::path jsonPath = folder / "pca.json";
  PIXELCLOTH_CHECK(std::filesystem::is_regular_file(jsonPath),
                   jsonPath.string() << ": no PCA filter here (expected pca.json from pixelcloth pca, or evaluate "
                                        "--stitch pca:K fits one beside the model)");
  PcaFilter filter;
  filter.info_ = core::readJson(jsonPath);
  const std::string context = jsonPath.string();
  PIXELCLOTH_CHECK(core::requireValue<std::string>(filter.info_, "format", context) == kFormat,
                   context << ": format '" << filter.info_["format"].get<std::string>() << "', expected " << kFormat);
  const int V = core::requireValue<int>(filter.info_, "vertices", context);
  const int rank = core::requireValue<int>(filter.info_, "rank", context);
  PIXELCLOTH_CHECK(V >= 1 && rank >= 1, context << ": vertices " << V << ", rank " << rank << ", expected >= 1");
  const nlohmann::json& files = core::requireField(filter.info_, "files", context);
  for (const char* name : {"mean.npy", "components.npy", "variance.npy"}) {
    const std::filesystem::path path = folder / name;
    PIXELCLOTH_CHECK(std::filesystem::is_regular_file(path), path.string() << ": missing (pca.json lists it)");
    const auto expected = core::requireValue<std::uint32_t>(files, name, context + " files");
    const std::uint32_t crc = data::fileCrc32(path);
    PIXELCLOTH_CHECK(crc == expected, path.string() << ": CRC-32 " << crc << ", pca.json says " << expected
                                                    << " (the file was altered or truncated; fit the filter again)");
  }
  filter.basis_.mean = core::readNpyMatrixF(folder / "mean.npy", 1, 3LL * V).transpose();
  filter.basis_.components = core::readNpyMatrixF(folder / "components.npy", rank, 3LL * V);
  filter.basis_.variance = core::readNpyMatrixF(folder / "variance.npy", 1, rank).transpose();
  PIXELCLOTH_CHECK(filter.basis_.mean.allFinite() && filter.basis_.components.allFinite(),
                   folder.string() << ": the PCA filter holds values that are not finite");
  filter.folder_ = folder;
  return filter;
}

void PcaFilter::checkMatches(const std::string& garment, int numVertices, learn::OffsetSpace space) const {
  const std::string where = folder_.empty() ? std::string("pca filter") : (folder_ / "pca.json").string();
  const std::string itsGarment = core::valueOr<std::string>(info_, "garment", "?", where);
  const int itsVertices = core::valueOr(info_, "vertices", 0, where);
  const std::string itsSpace = core::valueOr<std::string>(info_, "space", "?", where);
  PIXELCLOTH_CHECK(itsGarment == garment && itsVertices == numVertices,
                   where << ": a filter of the " << itsGarment << " with " << itsVertices << " vertices, expected the "
                         << garment << " with " << numVertices);
  PIXELCLOTH_CHECK(itsSpace == learn::offsetSpaceName(space),
                   where << ": values in space " << itsSpace << ", expected "
                         << learn::offsetSpaceName(space) << " (the model's)");
}

void PcaFilter::checkMatches(const learn::TrainingData& data) const {
  checkMatches(data.garment.name, data.garment.mesh.numVertices(), data.space);
  const std::string where = folder_.empty() ? std::string("pca filter") : (folder_ / "pca.json").string();
  const auto crc = core::valueOr(info_, "dataset_manifest_crc32", std::uint32_t{0}, where);
  PIXELCLOTH_CHECK(crc == data.manifestCrc,
                   where << ": fitted on " << core::valueOr<std::string>(info_, "dataset", "?", where) << " (manifest CRC-32 " << crc
                         << "), not on " << data.folder.string() << " (" << data.manifestCrc
                         << "); fit one on this dataset with pixelcloth pca");
}

Eigen::MatrixXf PcaFilter::filter(const Eigen::MatrixXf& values, int k) const {
  PIXELCLOTH_CHECK(k >= 1 && k <= rank(), "pca:" << k << ": the filter"
                                                 << (folder_.empty() ? "" : " in " + folder_.string())
                                                 << " was fitted with rank " << rank() << ", expected k from 1 to "
                                                 << rank());
  PIXELCLOTH_CHECK(values.cols() == basis_.mean.size(),
                   "pca filter: " << values.cols() << " values per garment, expected " << basis_.mean.size());
  const Eigen::MatrixXf& top = basis_.components.topRows(k);
  const Eigen::MatrixXf centred = values.rowwise() - basis_.mean.transpose();
  return (centred * top.transpose() * top).rowwise() + basis_.mean.transpose();
}

std::filesystem::path defaultPcaFolder(const std::filesystem::path& modelFolder) { return modelFolder / "pca"; }

PcaFilter loadOrFitPcaFilter(const learn::TrainingData& data, const std::filesystem::path& modelFolder,
                             const std::filesystem::path& folder, int rank) {
  if (!folder.empty()) {
    PcaFilter filter = PcaFilter::load(folder);
    if (data.train.empty())  // one pose: no dataset rows to check against
      filter.checkMatches(data.garment.name, data.garment.mesh.numVertices(), data.space);
    else
      filter.checkMatches(data);
    return filter;
  }
  const std::filesystem::path saved = defaultPcaFolder(modelFolder);
  if (std::filesystem::is_regular_file(saved / "pca.json")) {
    PcaFilter filter = PcaFilter::load(saved);
    bool matches = true;
    try {
      if (!data.train.empty()) filter.checkMatches(data);
    } catch (const core::InputError&) {
      matches = false;
      PIXELCLOTH_INFO(saved.string() << ": fitted on another dataset; fitting again on " << data.folder.string());
    }
    if (matches && (rank == 0 || rank == filter.rank())) return filter;
  }
  PIXELCLOTH_CHECK(!data.train.empty(), "--stitch pca:K: " << saved.string()
                                                           << " holds no PCA filter of this model's dataset; fit one "
                                                              "with pixelcloth pca or evaluate --stitch pca:K first, "
                                                              "or give --pca DIR");
  PcaFilter filter = PcaFilter::fit(data, rank);
  filter.save(saved);
  return filter;
}

}  // namespace pixelcloth::stitch
