// The demo's own-garment section: a T-shirt OBJ written the way other cloth programs write theirs (tube sleeves with
// several UVs per vertex, Z up, centimetres, another origin) is imported without a cage file and taken through the
// pipeline as a garment folder: fitted to the body (its cage lines and patches), dressing, simulation, markers,
// reconstruction, a per-patch model, prediction and evaluation.
#include <iomanip>
#include <sstream>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/garment/obj_import.h"
#include "pixelcloth/learn/predict.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/learn/training_data.h"
#include "pixelcloth/patches/body_fit.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/recon/reconstruct.h"
#include "pixelcloth/sim/generate.h"
#include "pixelcloth/stitch/evaluate.h"
#include "pixelcloth/viz/demo.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/previews.h"

namespace pixelcloth::viz {

namespace fs = std::filesystem;

void demoOwnGarment(Report& report, const body::Body& body, const DemoOptions& demo) {
  const fs::path folder = report.folder() / "own_garment";
  const fs::path garmentFolder = folder / "garment", datasetFolder = folder / "dataset";
  nlohmann::json& figures = report.json()["own_garment"];
  figures = nlohmann::json::object();
  report.step("your own garment: a T-shirt OBJ as other programs write it, imported without a cage file", [&] {
    report.freshFolder("own_garment");
    // The file a user brings: each sleeve one tube-shaped UV island cut along the underarm (its vertices hold two UVs
    // there), Z up, in centimetres, its origin 90 cm below and 5 cm behind the body's.
    garment::TShirtOptions shirt;
    shirt.targetVertices = 2000;
    garment::ObjExportOptions file;
    file.tubeSleeves = true;
    file.up = 'z';
    file.scale = 0.01;
    file.translate = Eigen::Vector3d(0, 0.9, 0.05);
    file.shuffleSeed = 7;
    garment::exportGarmentObj(garment::makeTShirt(shirt), folder / "shirt.obj", file);
    const core::Mesh raw = core::readMesh(folder / "shirt.obj");
    garment::ObjImportOptions placement;
    placement.name = "my_shirt";
    placement.up = 'z';
    placement.scale = 0.01;
    placement.translate = file.translate;
    garment::ObjImportReport notes;
    garment::Garment imported = garment::importGarmentObj(folder / "shirt.obj", placement, &notes);
    const size_t piecePatches = patches::garmentPatches(imported).size();
    // `garment --import ... --fit-to BODY`: the body loops, centre lines and splits that give it patches.
    const patches::BodyFitReport fit = patches::fitGarmentToBody(imported, body);
    garment::saveGarment(garmentFolder, imported);
    writePng(garmentFolder / "pattern.png", renderPattern(imported));
    writePng(garmentFolder / "garment.png", renderGarmentOnBody(imported, &body));
    figures["file"] = {{"vertices", raw.numVertices()}, {"uvs", raw.UV.rows()}, {"faces", raw.numFaces()}};
    figures["import"] = {{"summary", imported.summary()}, {"fixes", notes.summary()}};
    figures["fit"] = {{"summary", fit.summary()},
                      {"patches_before", piecePatches},
                      {"patches", fit.patches},
                      {"largest_patch_px", fit.largestPatchPixels}};

    const cage::Dressing dressing =
        cage::dressGarment(body, cage::bodyCage(body), imported, cage::garmentCage(imported));
    writeDressingFolder(body, imported, dressing, folder / "dressing");
    figures["dressing"] = dressing.summary();
  });
  report.step("your own garment: simulated, checked, rebuilt from markers", [&] {
    sim::GenerateOptions generate;
    generate.garment = garmentFolder.string();  // the folder, as `generate --garment DIR` takes it
    generate.count = demo.ownGarmentSamples;
    generate.seed = demo.seed;
    generate.bodyFolder = report.folder() / "body";
    const sim::GenerateReport made = sim::generateDataset(datasetFolder, generate);
    const data::DatasetCheckReport checked = data::checkDataset(datasetFolder);
    const data::Dataset dataset = data::openDataset(datasetFolder);
    figures["dataset"] = {{"samples", dataset.rows()},
                          {"seconds", made.seconds},
                          {"check", checked.summary()},
                          {"stats", dataset.info.stats.toJson()}};
    recon::DatasetReconstructionOptions options;
    options.split.reset();  // every row
    options.meshes = 1;
    const recon::DatasetReconstructionReport rec =
        recon::reconstructDataset(datasetFolder, folder / "reconstruction", options);
    figures["reconstruction"] = {{"markers", rec.metrics["markers"]},
                                 {"spline_garment_cm", rec.metrics["methods"]["spline"]["garment_cm"]},
                                 {"linear_garment_cm", rec.metrics["methods"]["linear"]["garment_cm"]}};
  });
  report.step("your own garment: per-patch decoders trained, predicted and evaluated", [&] {
    // The paper's per-patch decoders (section 5), as small as the template's in the learning section.
    learn::TrainOptions options;
    options.model.architecture = learn::Architecture::Patch;
    options.model.width = 0.125;
    options.epochs = demo.learningEpochs;
    options.batch = 4;
    options.learningRate = 2e-3;
    const fs::path modelFolder = folder / "model_patch";
    const learn::TrainReport trained = learn::train(datasetFolder, modelFolder, options);
    writePng(modelFolder / "training.png",
             renderTrainingCurves(trained.networks.front(),
                                  "my_shirt patch " + std::to_string(trained.networks.front().patch)));
    const garment::Garment shirt = data::datasetGarment(data::readDatasetInfo(datasetFolder));
    const learn::TrainedModel model(modelFolder, shirt);
    const learn::TrainingData data = learn::loadTrainingData(datasetFolder, model.space(), fs::path());
    const data::Split split = data.test.empty() ? data::Split::Train : data::Split::Test;
    const stitch::Evaluation evaluation = stitch::evaluate(model, data, split).front();
    const std::vector<int>& rows = data.split(split);
    const std::vector<int> shown(rows.begin(), rows.begin() + std::min<size_t>(2, rows.size()));
    const stitch::RowPredictions predicted = stitch::predictRows(model, data, shown);
    std::vector<core::RgbImage> pictures;
    for (size_t k = 0; k < shown.size(); ++k) {
      body::Body posed = body;
      posed.mesh = body.posedMesh(body::Pose::fromLeading(data.inputs.row(shown[k]).head(data.poseSize).transpose()));
      garment::Garment truth = shirt, guess = shirt;
      truth.mesh.V = data.truth[shown[k]].cast<double>();
      guess.mesh.V = predicted.positions[k];
      core::RgbImage left = renderGarmentOnBody(truth, &posed, 240), right = renderGarmentOnBody(guess, &posed, 240);
      drawText(left, {8, 8}, "ground truth", {0, 0, 0}, 2);
      std::ostringstream label;
      label << std::fixed << std::setprecision(2) << "patches "
            << core::meanVertexErrorCm(predicted.positions[k], data.truth[shown[k]]) << " cm";
      drawText(right, {8, 8}, label.str(), {0, 0, 0}, 2);
      pictures.push_back(left);
      pictures.push_back(right);
    }
    writePng(folder / "predictions.png", contactSheet(pictures, 2));
    figures["learning"] = {{"model", "patch"},
                           {"networks", trained.networks.size()},
                           {"width", options.model.width},
                           {"epochs", options.epochs},
                           {"seconds", trained.seconds},
                           {"split", data::splitName(split)},
                           {"samples", evaluation.metrics["samples"]},
                           {"vertex_error_cm", evaluation.metrics["vertex_error_cm"]}};
  });
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
