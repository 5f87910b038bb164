#include "pixelcloth/recon/capture_base.h"

#include "pixelcloth/cage/geodesic.h"
#include "pixelcloth/cage/length_model.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/recon/base.h"
#include "pixelcloth/recon/reconstruct.h"

namespace pixelcloth::recon {

namespace fs = std::filesystem;

struct CaptureRebuilder::Impl {
  std::unique_ptr<GarmentReconstructor> reconstructor;
  cage::MarkerSet definition;
};

CaptureRebuilder::CaptureRebuilder(const fs::path& baseFolder, const data::DatasetFolder& where)
    : impl_(std::make_unique<Impl>()) {
  const fs::path& dataset = where.path;
  const fs::path manifestPath = baseFolder / "manifest.json";
  const std::string context = manifestPath.string();
  const nlohmann::json manifest = core::readJson(manifestPath);
  const data::DatasetInfo info = data::readDatasetInfo(where);
  const std::string format = core::valueOr<std::string>(manifest, "format", "", context);
  PIXELCLOTH_CHECK(format == "pixelcloth.base", context << ": not a base folder's manifest (format '" << format << "')");
  PIXELCLOTH_CHECK(core::valueOr(manifest, "dataset_manifest_crc32", 0u, context) ==
                       data::fileCrc32(dataset / "manifest.json"),
                   context << ": made from another dataset than " << dataset.string());
  const nlohmann::json settings = core::requireField(manifest, "settings", context);
  ReconstructionOptions options;
  options.bodyClearance = core::requireValue<double>(settings, "body_clearance_m", context);
  options.spline.restLengths =
      cage::restLengthsFromName(core::requireValue<std::string>(settings, "rest_lengths", context), context);
  options.spline.markerSigma = core::requireValue<double>(settings, "marker_sigma_m", context);
  const nlohmann::json anisotropic = core::requireField(settings, "anisotropic", context);
  options.anisotropic = {true, core::requireValue<double>(anisotropic, "theta", context),
                         core::requireValue<double>(anisotropic, "ratio", context)};
  const nlohmann::json lengthModel = settings.value("length_model", nlohmann::json());
  if (lengthModel.is_object() && lengthModel.contains("model"))
    options.lengthModel = cage::lengthModelFromJson(lengthModel["model"], context + ": length_model");

  const body::Body body = data::loadDatasetBody(where);
  const garment::Garment garment = data::datasetGarment(info);
  const garment::Embedding embedding = data::loadDatasetEmbedding(where, body.mesh.F.rows());
  impl_->reconstructor = std::make_unique<GarmentReconstructor>(
      body, garment, embedding, data::loadDatasetRestPositions(where, garment.mesh.numVertices()), options);
  cage::MarkerOptions markerOptions;
  markerOptions.spacing = core::requireValue<double>(settings, "marker_spacing_m", context);
  impl_->definition = cage::defineMarkers(garment, impl_->reconstructor->cage(), markerOptions);
  const cage::MarkerSet& definition = impl_->definition;
  const nlohmann::json names = core::requireField(settings, "marker_names", context);
  PIXELCLOTH_CHECK(names.is_array() && names.size() == definition.markers.size(),
                   context << ": " << names.size() << " marker names, but the " << garment.name << "'s markers at "
                           << markerOptions.spacing << " m spacing are " << definition.markers.size());
  for (size_t k = 0; k < names.size(); ++k)
    PIXELCLOTH_CHECK(names[k] == definition.markers[k].name, context << ": marker " << k + 1 << " is '"
                                                                     << names[k].get<std::string>() << "', expected '"
                                                                     << definition.markers[k].name << "'");
}

CaptureRebuilder::~CaptureRebuilder() = default;

const cage::MarkerSet& CaptureRebuilder::definition() const { return impl_->definition; }
const GarmentReconstructor& CaptureRebuilder::reconstructor() const { return *impl_->reconstructor; }

CaptureBase CaptureRebuilder::rebuild(const cage::MarkerSet& captured, const body::Pose& pose,
                                      const std::string& markersContext) const {
  const GarmentReconstructor& reconstructor = *impl_->reconstructor;
  captured.validate(reconstructor.garment(), reconstructor.cage(), markersContext, true);
  const PosedBody posed = reconstructor.posed(pose);
  CaptureBase base;
  base.offsets = reconstructor.reconstruct(captured, posed, ReconstructionMethod::SplineAnisotropic).offsets;
  base.features = markerFeatures(impl_->definition, captured, posed.frames());
  return base;
}

CaptureBase baseOfCapture(const fs::path& baseFolder, const data::DatasetFolder& where, const cage::MarkerSet& captured,
                          const body::Pose& pose, const std::string& markersContext) {
  return CaptureRebuilder(baseFolder, where).rebuild(captured, pose, markersContext);
}

}  // namespace pixelcloth::recon
