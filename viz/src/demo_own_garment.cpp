// The demo's own-garment section (eval::runOwnGarment) drawn: a T-shirt OBJ written the way other cloth programs write
// theirs, imported without a cage file and taken through the pipeline as a garment folder: its pattern with the fitted
// cage lines, its dressing, a prediction beside ground truth, and the figures of every stage.
#include <iomanip>
#include <sstream>

#include "pixelcloth/core/measure.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"

namespace pixelcloth::viz {

void demoOwnGarment(Report& report, const body::Body& body, const eval::OwnGarment& own) {
  nlohmann::json& figures = report.json()["own_garment"];
  figures = nlohmann::json::object();
  writePng(own.garmentFolder / "pattern.png", renderPattern(own.garment));
  writePng(own.garmentFolder / "garment.png", renderGarmentOnBody(own.garment, &body));
  writeDressingFolder(body, own.garment, own.dressing, own.folder / "dressing");
  figures["file"] = {{"vertices", own.fileVertices}, {"uvs", own.fileUvs}, {"faces", own.fileFaces}};
  figures["import"] = {{"summary", own.garment.summary()}, {"fixes", own.import.summary()}};
  figures["fit"] = {{"summary", own.fit.summary()},
                    {"patches_before", own.piecePatches},
                    {"patches", own.fit.patches},
                    {"largest_patch_px", own.fit.largestPatchPixels}};
  figures["dressing"] = own.dressing.summary();
  figures["dataset"] = {{"samples", own.dataset.info.settings.rows()},
                        {"seconds", own.dataset.seconds},
                        {"check", own.dataset.check.summary()},
                        {"stats", own.dataset.info.stats.toJson()}};
  const nlohmann::json& rec = own.reconstruction.metrics;
  figures["reconstruction"] = {{"markers", rec["markers"]},
                               {"spline_garment_cm", rec["methods"]["spline"]["garment_cm"]},
                               {"linear_garment_cm", rec["methods"]["linear"]["garment_cm"]}};

  const eval::DemoModel& model = own.model;
  const learn::TrainingData& data = own.data;
  writePng(model.folder / "training.png",
           renderTrainingCurves(model.trained.networks.front(),
                                own.garment.name + " patch " + std::to_string(model.trained.networks.front().patch)));
  std::vector<core::RgbImage> pictures;
  for (size_t k = 0; k < own.shown.size(); ++k) {
    const int row = own.shown[k];
    body::Body posed = body;
    posed.mesh = body.posedMesh(body::Pose::fromLeading(data.inputs.row(row).head(data.poseSize).transpose()));
    garment::Garment truth = data.garment, guess = data.garment;
    truth.mesh.V = data.truth[row].cast<double>();
    guess.mesh.V = model.shown.positions[k];
    core::RgbImage left = renderGarmentOnBody(truth, &posed, 240), right = renderGarmentOnBody(guess, &posed, 240);
    drawText(left, {8, 8}, "ground truth", {0, 0, 0}, 2);
    std::ostringstream label;
    label << std::fixed << std::setprecision(2) << "patches "
          << core::meanVertexErrorCm(model.shown.positions[k], data.truth[row]) << " cm";
    drawText(right, {8, 8}, label.str(), {0, 0, 0}, 2);
    pictures.push_back(left);
    pictures.push_back(right);
  }
  writePng(own.folder / "predictions.png", contactSheet(pictures, 2));
  figures["learning"] = {{"model", "patch"},
                         {"networks", model.trained.networks.size()},
                         {"width", model.options.model.width},
                         {"epochs", model.options.epochs},
                         {"seconds", model.trained.seconds},
                         {"split", data::splitName(model.split)},
                         {"samples", model.evaluation.metrics["samples"]},
                         {"vertex_error_cm", model.evaluation.metrics["vertex_error_cm"]}};
  std::ostringstream text;
  text << std::fixed << std::setprecision(2);
  const nlohmann::json& f = figures;
  text << "A T-shirt written as another cloth program writes one (own_garment/shirt.obj: "
       << f["file"]["vertices"].get<int>() << " vertices with " << f["file"]["uvs"].get<int>()
       << " UVs, each sleeve a tube-shaped UV island cut along its underarm, Z up, in centimetres, its origin 90 cm "
          "below the body's), imported by `pixelcloth garment --import shirt.obj --up z --scale 0.01 --translate 0 "
          "0.9 0.05` with no cage file: "
       << f["import"]["summary"].get<std::string>() << " (" << f["import"]["fixes"].get<std::string>()
       << "). Its seams and openings are named by where they sit; that gives one patch per pattern piece ("
       << f["fit"]["patches_before"].get<int>() << "). Fitted to the mannequin (`--fit-to`), it gets the "
       << "template's body loops, centre lines and side-panel splits where the body's cage meets it, and patches split "
          "until each fits 128 px of its 512 px layout image: "
       << f["fit"]["summary"].get<std::string>() << ". It dresses on the body cage like the template: "
       << f["dressing"].get<std::string>() << ". As a garment folder it goes wherever a template name goes: "
       << "`generate --garment own_garment/garment` simulated " << f["dataset"]["samples"].get<int>()
       << " samples (" << f["dataset"]["check"].get<std::string>() << "); rebuilt from its own "
       << f["reconstruction"]["markers"].get<int>() << " markers the spline gives "
       << f["reconstruction"]["spline_garment_cm"].get<double>() << " cm (linear "
       << f["reconstruction"]["linear_garment_cm"].get<double>() << " cm); " << f["learning"]["networks"].get<int>()
       << " per-patch decoders (width " << f["learning"]["width"].get<double>() << ", "
       << f["learning"]["epochs"].get<int>() << " epochs, " << f["learning"]["seconds"].get<double>()
       << " s) predict its " << f["learning"]["split"].get<std::string>() << " split at "
       << f["learning"]["vertex_error_cm"].get<double>() << " cm over " << f["learning"]["samples"].get<int>()
       << " samples (too few to generalise: it shows the path works). Pictures: the imported pattern with its fitted "
          "cage lines (six layouts: torso front and back, each sleeve cut along its top), the garment on the body, "
          "and a prediction beside ground truth.";
  report.section("Your own garment", text.str(),
                 {"own_garment/garment/pattern.png", "own_garment/dressing/dressed.png", "own_garment/predictions.png"});
}

}  // namespace pixelcloth::viz
