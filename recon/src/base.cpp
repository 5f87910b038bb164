// Base offsets and marker features of every dataset row, for the learned refinement (DESIGN.md, "Learned refinement").
#include "pixelcloth/recon/base.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <memory>
#include <sstream>
#include <vector>

#include "dataset_internal.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/parallel.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/base_set.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::recon {

namespace fs = std::filesystem;

Eigen::VectorXd markerFeatures(const cage::MarkerSet& definition, const cage::MarkerSet& captured,
                               const garment::EmbeddedFrames& frames) {
  const int M = static_cast<int>(definition.markers.size());
  // The captured markers, matched to the definition in order (placeMarkers keeps it and only leaves markers out).
  std::vector<int> rows;  // definition index of each captured marker
  size_t next = 0;
  for (int i = 0; i < M && next < captured.markers.size(); ++i)
    if (captured.markers[next].name == definition.markers[i].name) {
      rows.push_back(i);
      ++next;
    }
  PIXELCLOTH_CHECK(next == captured.markers.size(), "marker features: captured marker '"
                                                        << captured.markers[next].name
                                                        << "' is not in the marker definition, or out of its order");
  garment::EmbeddedFrames picked;
  const int n = static_cast<int>(rows.size());
  picked.origin.resize(n, 3);
  picked.t.resize(n, 3);
  picked.b.resize(n, 3);
  picked.n.resize(n, 3);
  Eigen::MatrixX3d positions(n, 3);
  for (int k = 0; k < n; ++k) {
    const cage::Marker& marker = captured.markers[k];
    PIXELCLOTH_CHECK(marker.vertex >= 0 && marker.vertex < frames.origin.rows() && marker.hasPosition(),
                     "marker features: marker '" << marker.name << "' has vertex " << marker.vertex << " of "
                                                 << frames.origin.rows()
                                                 << (marker.hasPosition() ? "" : ", no position"));
    picked.origin.row(k) = frames.origin.row(marker.vertex);
    picked.t.row(k) = frames.t.row(marker.vertex);
    picked.b.row(k) = frames.b.row(marker.vertex);
    picked.n.row(k) = frames.n.row(marker.vertex);
    positions.row(k) = marker.position.transpose();
  }
  const Eigen::MatrixX3d offsets = garment::offsetsFromPositions(picked, positions);
  Eigen::VectorXd features = Eigen::VectorXd::Zero(3 * M);
  for (int k = 0; k < n; ++k) features.segment<3>(3 * rows[k]) = offsets.row(k).transpose();
  return features;
}

void BaseSetOptions::validate() const {
  markers.validate();
  capture.validate();
  reconstruction.validate();
  PIXELCLOTH_CHECK(lengthModel.kind != LengthModelSource::Kind::File || !lengthModel.file.empty(),
                   "bases: the length model file is empty");
  lengthModelFit.validate();
  PIXELCLOTH_CHECK(threads >= 0 && threads <= 256,
                   "bases: threads " << threads << ", expected 0 (one per core) to 256");
}

std::string BaseSetReport::summary() const {
  std::ostringstream out;
  out << samples << " samples, " << markers << " markers, spline_anisotropic: garment error " << std::fixed
      << std::setprecision(3) << meanErrorCm << " cm, " << std::setprecision(2) << pushedOutPercent << "% pushed out, "
      << std::setprecision(1) << seconds << " s";
  return out.str();
}

BaseSetReport writeDatasetBases(const data::DatasetFolder& where, const fs::path& out, const BaseSetOptions& options) {
  const fs::path& datasetFolder = where.path;
  options.validate();
  core::checkOutputFolder(out);
  std::error_code ec;
  PIXELCLOTH_CHECK(!fs::exists(out, ec) || !fs::equivalent(out, datasetFolder, ec),
                   out.string() << ": is the dataset folder; the base folder's manifest.json would replace the "
                                   "dataset's: give it a folder of its own");
  const data::Dataset dataset = data::openDataset(where);
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<GarmentReconstructor> reconstructor =
      detail::datasetReconstructor(dataset, options.reconstruction);
  const cage::MarkerSet definition =
      cage::defineMarkers(reconstructor->garment(), reconstructor->cage(), options.markers);
  const nlohmann::json lengthModel = detail::useLengthModel(*reconstructor, dataset, definition, options.lengthModel,
                                                            options.markers.spacing, options.lengthModelFit);
  const int rows = dataset.rows(), V = dataset.vertexCount(), M = static_cast<int>(definition.markers.size());

  Eigen::MatrixXf offsets(rows, 3 * V), features(rows, 3 * M);
  std::vector<double> errorCm(rows, 0), pushed(rows, 0);
  auto rebuild = [&](int r) {
    const Eigen::MatrixX3d truth = dataset.positionsOf(r).cast<double>();
    const cage::MarkerSet markers =
        detail::captureMarkers(definition, truth, options.capture, dataset.info.settings.first() + r);
    const PosedBody posed = reconstructor->posed(detail::poseOfRow(dataset, r));
    const Reconstruction rec = reconstructor->reconstruct(markers, posed, ReconstructionMethod::SplineAnisotropic);
    // fillFromCage recomputes the offsets of vertices the body clearance moved, so these are the final positions'.
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rowMajor = rec.offsets;
    offsets.row(r) = Eigen::Map<const Eigen::RowVectorXd>(rowMajor.data(), 3 * V).cast<float>();
    features.row(r) = markerFeatures(definition, markers, posed.frames()).transpose().cast<float>();
    errorCm[r] = core::meanVertexErrorCm(rec.positions, truth);
    pushed[r] = static_cast<double>(rec.pushedOut) / V;
  };

  auto progress = std::make_unique<core::Progress>("bases", rows);
  core::parallelFor(rows, options.threads, [&](int r) {
    try {
      rebuild(r);
    } catch (const core::InputError& e) {
      // Which sample's markers could not be solved (dropout can leave a closed curve too few).
      PIXELCLOTH_FAIL(datasetFolder.string() << ": sample " << dataset.info.settings.first() + r << ": " << e.what());
    }
    progress->advance();
  });
  progress->finish();

  BaseSetReport report;
  report.samples = rows;
  report.markers = M;
  for (int r = 0; r < rows; ++r) {
    report.meanErrorCm += errorCm[r] / rows;
    report.pushedOutPercent += 100 * pushed[r] / rows;
  }
  nlohmann::json names = nlohmann::json::array();
  for (const cage::Marker& marker : definition.markers) names.push_back(marker.name);
  nlohmann::json lengthModelJson = lengthModel;
  if (reconstructor->solver().lengthModel())
    lengthModelJson["model"] = cage::toJson(*reconstructor->solver().lengthModel());
  const nlohmann::json settings = {
      {"method", reconstructionMethodName(ReconstructionMethod::SplineAnisotropic)},
      {"marker_spacing_m", options.markers.spacing},
      {"marker_names", names},
      {"noise_cm", 100 * options.capture.noise},
      {"dropout", options.capture.dropout},
      {"seed", options.capture.seed},
      {"body_clearance_m", options.reconstruction.bodyClearance},
      {"rest_lengths", cage::restLengthsName(options.reconstruction.spline.restLengths)},
      {"marker_sigma_m", options.reconstruction.spline.markerSigma},
      {"anisotropic",
       {{"theta", options.reconstruction.anisotropic.theta}, {"ratio", options.reconstruction.anisotropic.ratio}}},
      {"length_model", lengthModelJson}};
  data::writeBaseSet(out, dataset.info, offsets, features, settings);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace pixelcloth::recon
