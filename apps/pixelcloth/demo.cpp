// pixelcloth demo: everything that exists, end to end, on the built-in body and garments, as a report
// folder of pictures (index.html, report.json).
#include <chrono>
#include <fstream>
#include <iomanip>
#include <memory>
#include <sstream>

#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/body/body.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/viz/basis_figures.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/edit.h"
#include "pixelcloth/patches/garment_fill.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/sim/generate.h"
#include "pixelcloth/viz/pose_figures.h"
#include "pixelcloth/sim/pose_sampler.h"
#include "pixelcloth/recon/reconstruct.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
namespace fs = std::filesystem;
using namespace pixelcloth::core;
using namespace pixelcloth::body;
using namespace pixelcloth::garment;
using namespace pixelcloth::viz;

struct DemoArgs {
  std::string out;
  int poses = 12;
  int filterPoses = 200;   ///< poses drawn, pruned and simulated for the filtering histograms
  int tshirtSamples = 40;  ///< the simulated T-shirt dataset; its test split is rebuilt from markers
  std::uint64_t seed = 1;
};

/// Times one demo step and records it in the report.
class Steps {
 public:
  explicit Steps(nlohmann::json& report) : report_(report) {}
  template <typename F>
  void run(const std::string& name, F&& step) {
    PIXELCLOTH_INFO("demo: " << name << " ...");
    auto start = std::chrono::steady_clock::now();
    step();
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_["steps"].push_back({{"name", name}, {"seconds", seconds}});
    PIXELCLOTH_INFO("demo: " << name << " done in " << formatDuration(seconds) << " (" << seconds << " s)");
  }

 private:
  nlohmann::json& report_;
};

/// Arms raised and bent, torso twisted: a pose where weight errors show.
Pose showPose() {
  Eigen::Matrix<double, 10, 3> e = Eigen::Matrix<double, 10, 3>::Zero();
  e(2, 1) = 10;   // spine twist
  e(5, 2) = 55;   // l_arm up
  e(6, 1) = -70;  // l_forearm bent forward
  e(8, 2) = 20;   // r_arm down a little (right side mirrors)
  e(8, 1) = 40;   // r_arm forward
  return Pose::fromEulerDegrees(e);
}

void writeIndex(const fs::path& out, const nlohmann::json& report) {
  std::ostringstream html;
  html << "<!doctype html><html><head><meta charset='utf-8'><title>pixelcloth demo</title>"
       << "<style>body{font-family:sans-serif;max-width:1400px;margin:2em auto;color:#222}img{max-width:100%;"
       << "border:1px solid #ddd}td,th{padding:2px 10px;text-align:left}</style></head><body>"
       << "<h1>pixelcloth demo report</h1><p>Everything the toolkit does so far, on the built-in mannequin and "
       << "garments. Numbers are in <code>report.json</code>.</p>";
  for (const auto& section : report["sections"]) {
    html << "<h2>" << section["title"].get<std::string>() << "</h2><p>" << section["text"].get<std::string>() << "</p>";
    for (const auto& picture : section["pictures"]) html << "<p><img src='" << picture.get<std::string>() << "'></p>";
  }
  html << "<h2>Timings</h2><table><tr><th>step</th><th>seconds</th></tr>";
  for (const auto& step : report["steps"])
    html << "<tr><td>" << step["name"].get<std::string>() << "</td><td>" << step["seconds"].get<double>()
         << "</td></tr>";
  html << "</table></body></html>\n";
  writeTextAtomically(out / "index.html", html.str());
}

void runDemo(const DemoArgs& args) {
  fs::path out(args.out);
  ensureOutputFolder(out);
  nlohmann::json report = {{"format", "pixelcloth.demo"},
                           {"version", 1},
                           {"steps", nlohmann::json::array()},
                           {"sections", nlohmann::json::array()}};
  Steps steps(report);
  auto section = [&](const std::string& title, const std::string& text, std::vector<std::string> pictures) {
    report["sections"].push_back({{"title", title}, {"text", text}, {"pictures", pictures}});
  };
  auto start = std::chrono::steady_clock::now();

  Body body;
  steps.run("body: built-in mannequin, skeleton, bone-heat weights, parts", [&] {
    body = makeMannequin();
    saveBody(out / "body", body, "built-in mannequin (demo)");
    writePng(out / "body" / "body.png", renderBodySheet(body));
    report["body"] = {{"vertices", body.mesh.numVertices()},
                      {"faces", body.mesh.numFaces()},
                      {"joints", body.skeleton.numJoints()},
                      {"height_m", body.mesh.V.col(1).maxCoeff()},
                      {"volume_m3", enclosedVolume(body.mesh.V, body.mesh.F)}};
  });
  section("Body",
          "The built-in mannequin (" + std::to_string(body.mesh.numVertices()) +
              " vertices, closed and manifold): shaded with its skeleton; bone-heat skin weights (a colour "
              "per joint); collision parts (left arm red, right arm blue, torso grey, overlaps purple); side.",
          {"body/body.png"});

  steps.run("body cage: loops, centre and side lines, armholes", [&] {
    cage::Cage bodyCage = cage::bodyCage(body);
    writeJson(out / "body" / "cage.json", cage::toJson(bodyCage));
    writePng(out / "body" / "cage.png", viz::renderCageOnMesh(body.mesh, bodyCage));
    report["body_cage"] = {{"curves", bodyCage.curves.size()}, {"nodes", bodyCage.nodes.size()}};
  });
  section("Body cage",
          "The cage on the mannequin, where the T-shirt's seams and loops will sit: chest, waist, hem, "
          "bicep and sleeve-hem loops (red / black), centre lines (blue), side, shoulder and armhole "
          "lines (green); yellow dots are junctions, named like the shirt's.",
          {"body/cage.png"});

  steps.run("body shapes: thinner (-1), default (0), thicker (2)", [&] {
    std::vector<RgbImage> pictures;
    View view;
    view.width = view.height = 400;
    view.azimuthDegrees = 25;
    for (double shape : {-1.0, 0.0, 2.0}) {
      MannequinOptions options;
      options.shape = shape;
      Body shaped = shape == 0.0 ? body : makeMannequin(options);
      view.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(-0.95, 0.7, -0.3), Eigen::Vector3d(0.95, 1.8, 0.3));
      pictures.push_back(renderPosedBody(shaped, Pose::identity(), view, false));
      report["shapes"].push_back({{"shape", shape}, {"volume_m3", enclosedVolume(shaped.mesh.V, shaped.mesh.F)}});
    }
    writePng(out / "shapes.png", contactSheet(pictures, 3));
  });
  section("Body shapes",
          "The shape parameter scales girth (-1 thinner, 0 default, 2 thicker), as the paper's "
          "intentionally modified body shapes.",
          {"shapes.png"});

  steps.run("skinning artifacts: corrupted upper-arm weights", [&] {
    std::vector<RgbImage> pictures;
    View view;
    view.width = view.height = 400;
    view.azimuthDegrees = 15;
    Pose pose = showPose();
    for (const std::string mode : {"", "torso", "torso+arm"}) {
      Body variant = body;
      if (!mode.empty()) variant.weights = corruptUpperArmWeights(body.skeleton, body.weights, mode, 0.5);
      pictures.push_back(renderPosedBody(variant, pose, view));
    }
    writePng(out / "skinning_artifacts.png", contactSheet(pictures, 3));
  });
  section("Skinning artifacts",
          "One pose with the bone-heat weights, then with half of each upper arm's weight moved "
          "to the torso, then to the torso and the opposite arm (the paper's experiment).",
          {"skinning_artifacts.png"});

  steps.run("poses: random poses within the joint limits", [&] {
    sim::PoseSamplerOptions options;
    options.seed = args.seed;
    sim::PoseSampler sampler(body, options);
    std::vector<Pose> poses = sampler.sample(args.poses);
    writePosedBodies(out / "poses", body, poses, {{"seed", args.seed}, {"sampler", "appendix"}});
    report["poses"] = {{"kept", sampler.stats().accepted},
                       {"rejected_arm_inside_torso", sampler.stats().rejectedArmInsideTorso}};
  });
  section("Posed bodies",
          "Poses from the paper's sampler (half-normal mixtures on the centre line; uniform azimuth, "
          "sine-altitude and twist for shoulders and arms, within the AAOS limits; poses with an arm inside the torso "
          "rejected), skinned by linear blend skinning; the skeleton is drawn over each.",
          {"poses/posed.png"});

  steps.run("import: an A-posed body brought back to the T-pose", [&] {
    fs::path folder = out / "import";
    ensureOutputFolder(folder);
    Pose pose = armsLowered(40);
    writeMesh(folder / "apose.obj", body.posedMesh(pose));
    nlohmann::json jointJson = nlohmann::json::object();
    for (const auto& [name, p] : posedJoints(body, pose)) jointJson[name] = {p.x(), p.y(), p.z()};
    writeJson(folder / "joints.json", {{"joints", jointJson}});
    // The same path a user takes: files in, body out.
    Body imported = importBody(readMesh(folder / "apose.obj"), readJointPositions(folder / "joints.json"),
                               (folder / "apose.obj").string());
    saveBody(folder / "body", imported, "imported A-pose demo body");
    View view;
    view.width = view.height = 420;
    view.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(-0.95, 0.7, -0.2), Eigen::Vector3d(0.95, 1.8, 0.2));
    Mesh asRead = readMesh(folder / "apose.obj");
    RgbImage before = renderMeshes({RenderMesh{asRead.V, asRead.F, {}, {}, {0.87, 0.78, 0.70}}}, view);
    RgbImage after = renderPosedBody(imported, Pose::identity(), view);
    writePng(folder / "import.png", contactSheet({before, after}, 2));
    report["import"] = {
        {"mean_vertex_distance_to_original_mm", 1000.0 * (imported.mesh.V - body.mesh.V).rowwise().norm().mean()}};
  });
  section("Body import",
          "An A-posed copy of the mannequin written as OBJ + joints JSON, imported back: weights "
          "recomputed, arms rotated into the T-pose (left: input; right: imported body).",
          {"import/import.png"});

  steps.run("garments: T-shirt and necktie sewing patterns", [&] {
    Garment shirt = makeTShirt();
    saveGarment(out / "tshirt", shirt);
    writePng(out / "tshirt" / "pattern.png", renderPattern(shirt));
    writePng(out / "tshirt" / "garment.png", renderGarmentOnBody(shirt, &body));
    Garment tie = makeNecktie();
    saveGarment(out / "necktie", tie);
    writePng(out / "necktie" / "pattern.png", renderPattern(tie));
    writePng(out / "necktie" / "garment.png", renderGarmentOnBody(tie, &body));
    report["tshirt"] = {{"summary", shirt.summary()},
                        {"meshing", shirt.meshing.summary(shirt.mesh.numVertices())},
                        {"length_m", shirt.length()}};
    report["necktie"] = {{"summary", tie.summary()}, {"meshing", tie.meshing.summary(tie.mesh.numVertices())}};
  });
  section("T-shirt pattern",
          "Front and back layouts (front, back, sleeve halves), triangulated by CGAL's constrained "
          "Delaunay mesher; seams in matching colours on both layouts, openings dark. " +
              report["tshirt"]["summary"].get<std::string>(),
          {"tshirt/pattern.png", "tshirt/garment.png"});
  section("Necktie pattern", report["necktie"]["summary"].get<std::string>(),
          {"necktie/pattern.png", "necktie/garment.png"});

  steps.run("cage and patches: T-shirt (28 patches) and necktie", [&] {
    writeCageFolder(makeTShirt(), out / "tshirt");
    writeCageFolder(makeNecktie(), out / "necktie");
  });
  section("Cage and patches",
          "Each garment's cage: seams (dark red), body loops (blue), centre lines (green), "
          "openings (black) and side-panel splits (orange); the T-shirt splits into 14 patches per "
          "side, each within 128 px of its side's 512 x 512 image. Lists in tshirt/patches.json.",
          {"tshirt/cage.png", "necktie/cage.png"});

  steps.run("patch bases: the appendix's figures", [&] { viz::writeBasisFigures(out / "bases"); });
  section("Patch bases",
          "Harmonic (left pair) and anisotropic (right pair, 30 degrees, ratio 0.1) fills of a 20 cm "
          "square patch from four boundary shapes: one bump, two bumps, a sine wave, an S-shaped "
          "boundary; height maps and shaded surfaces.",
          {"bases/bases.png"});

  steps.run("cloth images: a cage-driven fill, rasterised, edited", [&] {
    Garment shirt = makeTShirt();
    cage::Cage shirtCage = cage::garmentCage(shirt);
    patches::GarmentFill fill(shirt, patches::segmentPatches(shirt, cage::cutEdges(shirtCage)));
    // Offsets given on the cage only (a smooth wave in pattern space, centimetres), interiors from the bases.
    Eigen::MatrixX3d cageOffsets(shirt.mesh.numVertices(), 3);
    for (int v = 0; v < shirt.mesh.numVertices(); ++v) {
      int layout = shirt.vertexUV(v, 0) >= 0 ? 0 : 1;
      Eigen::Vector2d uv = shirt.mesh.UV.row(shirt.vertexUV(v, layout));
      cageOffsets.row(v) << 0.006 * std::sin(2 * M_PI * uv.y() / 0.5), 0.004 * std::cos(2 * M_PI * uv.x() / 0.4),
          0.01 + 0.008 * std::sin(2 * M_PI * (uv.x() + uv.y()) / 0.6);
    }
    Eigen::MatrixXf offsets = fill.fill(cageOffsets).cast<float>();
    patches::ClothImager imager(shirt);
    patches::ClothImage image = imager.rasterize(offsets);
    patches::writeClothImage(out / "images" / "filled.exr", image);
    // Edits of the appendix: a dn brush on the chest, then a shift of the whole image.
    patches::ClothImage edited = image;
    patches::brushImage(edited, {0.5 * image.width, 0.45 * image.height, 0.09 * image.width, 0.03f});
    patches::shiftImage(edited, 0.003f, 0.0f);
    patches::writeClothImage(out / "images" / "edited.exr", edited);
    viz::PreviewOptions preview;
    preview.range = 0.04f;
    writePng(out / "images" / "filled_and_edited.png",
             contactSheet({viz::renderClothImage(image, preview), viz::renderClothImage(edited, preview)}, 1));
    Eigen::MatrixXf back = imager.sample(image);
    report["cloth_image"] = {{"size", {image.width, image.height}},
                             {"round_trip_max_error_mm", 1e3 * (back - offsets).cwiseAbs().maxCoeff()}};
  });
  section("Cloth images",
          "Offsets set on the T-shirt's cage only (a smooth wave), patch interiors filled by their "
          "bases, rasterised to a 256 x 256 cloth image per side (RGB = du, dv, dn; padding dimmer). "
          "Below: the same image edited with a dn brush on the chest and a shift in du. EXR files in "
          "images/.",
          {"images/filled_and_edited.png"});

  steps.run("dressing: T-shirt and necktie on the mannequin", [&] {
    for (const Garment& garment : {makeTShirt(), makeNecktie()}) {
      const cage::Dressing dressing =
          cage::dressGarment(body, cage::bodyCage(body), garment, cage::garmentCage(garment));
      writeDressingFolder(body, garment, dressing, out / "dressing" / garment.name);
      report["dressing"][garment.name] = dressing.summary();
    }
  });
  section("Dressing",
          "The T-shirt's cage morphed onto the body cage, the rest carried by a Poisson solve, pushed out of the "
          "body and relaxed by edge-length equalisation on it: " +
              report["dressing"]["tshirt"].get<std::string>() +
              ". Area distortion in pattern space before and after relaxation (red stretch, blue compression), "
              "and the dressed shirt. The necktie keeps its rest placement.",
          {"dressing/tshirt/area_distortion.png", "dressing/tshirt/dressed.png"});

  // A small simulated dataset per garment, checked, with a contact sheet: posed body, draped garment, cloth image.
  auto simulatedDataset = [&](const std::string& name, int count) {
    const std::string folder = "dataset_" + name;
    // The demo owns its report folder: a dataset left there by an earlier version (other settings) would refuse to
    // resume, so each run makes its datasets afresh.
    fs::remove_all(out / folder);
    sim::GenerateOptions generate;
    generate.garment = name;
    generate.count = count;
    generate.seed = args.seed;
    generate.bodyFolder = out / "body";
    const sim::GenerateReport made = sim::generateDataset(out / folder, generate);
    const data::DatasetCheckReport checked = data::checkDataset(out / folder);
    const data::Dataset dataset = data::openDataset(out / folder);
    const Garment garment = name == "necktie" ? makeNecktie() : makeTShirt();
    patches::ClothImager imager(garment);
    viz::PreviewOptions preview;
    preview.range = 0.05f;
    std::vector<RgbImage> row;
    for (int r = 0; r < std::min(3, dataset.rows()); ++r) {
      const Pose pose = Pose::fromLeading(dataset.pose(r), "demo pose");
      Body posed = body;
      posed.mesh = body.posedMesh(pose);
      Garment draped = garment;
      draped.mesh.V = dataset.positionsOf(r).cast<double>();
      View view;
      view.width = view.height = 300;
      row.push_back(renderPosedBody(body, pose, view));
      row.push_back(renderGarmentOnBody(draped, &posed, 300));
      row.push_back(viz::renderClothImage(imager.rasterize(dataset.offsetsOf(r)), preview));
    }
    writePng(out / folder / "contact_sheet.png", contactSheet(row, 3));
    report[folder] = {{"samples", dataset.rows()},
                      {"seconds", made.seconds},
                      {"check", checked.summary()},
                      {"stats", dataset.info.stats.toJson()}};
  };
  steps.run("datasets: simulated T-shirt samples, checked; contact sheet",
            [&] { simulatedDataset("tshirt", args.tshirtSamples); });
  section("Simulated T-shirt dataset",
          "pixelcloth generate: poses from the appendix sampler, the dressed shirt settled under gravity, then "
          "walked to each pose in steps of at most 25 degrees per joint, the cloth carried with the body and relaxed "
          "against it (with friction); checked by dataset check (" +
              report["dataset_tshirt"]["check"].get<std::string>() +
              "); solver statistics and rejections: " + report["dataset_tshirt"]["stats"].dump() +
              ". Each row: posed body, simulated shirt (front, three-quarter, back), its cloth image.",
          {"dataset_tshirt/contact_sheet.png"});
  steps.run("reconstruction from markers: the T-shirt samples rebuilt by every method", [&] {
    // The spline's length model is fitted on the training split; the test split is rebuilt (every sample when the
    // dataset is too small to have one).
    const data::Dataset dataset = data::openDataset(out / "dataset_tshirt");
    recon::DatasetReconstructionOptions options;
    options.split = dataset.rowsOf(data::Split::Test).empty() ? "all" : "test";
    options.meshes = 2;
    const fs::path folder = out / "reconstruction";
    const recon::DatasetReconstructionReport rec = recon::reconstructDataset(out / "dataset_tshirt", folder, options);
    std::vector<int> shown;
    for (int r = 0; r < dataset.rows() && static_cast<int>(shown.size()) < 2; ++r)
      if (options.split == "all" || dataset.split[r] == static_cast<std::uint8_t>(data::Split::Test)) shown.push_back(r);
    const Garment shirt = data::datasetGarment(dataset.info);
    writePng(folder / "error_maps.png", renderReconstructionErrors(shirt, rec));
    std::vector<RgbImage> rows;
    for (int r : shown) {
      std::ostringstream sample;
      sample << "sample_" << std::setw(6) << std::setfill('0') << dataset.info.settings.first() + r;
      Body posed = body;
      posed.mesh = body.posedMesh(Pose::fromLeading(dataset.pose(r), "demo pose"));
      std::vector<RgbImage> row;
      for (const char* name : {"truth", "spline", "linear"}) {
        Garment g = shirt;
        g.mesh.V = readMesh(folder / sample.str() / (std::string(name) + ".obj")).V;
        RgbImage picture = renderGarmentOnBody(g, &posed, 260);
        drawText(picture, {8, 8}, name, {0, 0, 0}, 2);
        row.push_back(picture);
      }
      rows.push_back(contactSheet(row, 3));
    }
    writePng(folder / "comparison.png", contactSheet(rows, 1));
    nlohmann::json summary = rec.metrics;
    for (auto& [name, method] : summary["methods"].items()) method.erase("curves");
    report["reconstruction"] = summary;
  });
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2);
    for (const auto& [name, m] : report["reconstruction"]["methods"].items())
      text << name << ": cage " << m["cage_cm"].get<double>() << " cm, garment " << m["garment_cm"].get<double>()
           << " cm; ";
    section(
        "Reconstruction from markers",
        "pixelcloth reconstruct --dataset: markers at every cage junction and about every 10 cm along each curve (" +
            std::to_string(report["reconstruction"]["markers"].get<int>()) +
            ") taken from each simulated shirt; each cage curve drawn through them linearly, by Catmull-Rom, or "
            "by the length-preserving spline, whose segments keep the worn lengths a model fitted on the training "
            "split predicts (reconstruction/length_model.json); patch interiors filled from the cage by the "
            "isotropic (or anisotropic) bases, then kept 1 mm out of the posed body. Mean per-vertex error over the " +
            std::to_string(report["reconstruction"]["samples"].get<int>()) + " samples of the " +
            report["reconstruction"]["split"].get<std::string>() + " split: " + text.str() +
            "Rows: ground truth, spline, linear (front, back). Below: mean per-vertex error in pattern space per "
            "method (reconstruction/metrics.json has per-curve length errors).",
        {"reconstruction/comparison.png", "reconstruction/error_maps.png"});
  }
  steps.run("datasets: simulated necktie samples, checked; contact sheet", [&] { simulatedDataset("necktie", 6); });
  section("Simulated necktie dataset",
          "pixelcloth generate --garment necktie: poses from the appendix sampler (centre line only), quasistatic "
          "drape with the knot held at the collar; checked by dataset check (" +
              report["dataset_necktie"]["check"].get<std::string>() +
              "). Each row: posed body, simulated necktie, its cloth image (du dv dn).",
          {"dataset_necktie/contact_sheet.png"});

  steps.run("pose sampling: draws simulated on the T-shirt, joint-angle histograms before and after filtering", [&] {
    sim::PoseSamplerOptions options;
    options.seed = args.seed;
    sim::PoseSampler sampler(body, options);
    std::vector<Pose> drawn, survivors, kept;
    for (int k = 0; k < args.filterPoses; ++k) drawn.push_back(sampler.draw());
    data::DatasetStats tally;  // the same tally as a dataset's manifest: kept samples, rejections by reason
    for (const Pose& pose : drawn) {
      if (sampler.armInsideTorso(pose))
        tally.reject(data::Rejection::ArmInsideTorso);
      else
        survivors.push_back(pose);
    }
    const Garment shirt = makeTShirt();
    const cage::Dressing dressing = cage::dressGarment(body, cage::bodyCage(body), shirt, cage::garmentCage(shirt));
    const std::vector<data::SampleStats> stats = sim::simulatePoses(body, shirt, dressing, survivors);
    double seconds = 0;
    for (size_t k = 0; k < stats.size(); ++k) {
      seconds += stats[k].seconds;
      if (stats[k].rejection == data::Rejection::None) {
        kept.push_back(survivors[k]);
        tally.add(stats[k]);
      } else {
        tally.reject(stats[k].rejection);
      }
    }
    writePng(out / "poses" / "joint_histograms.png", viz::renderJointHistograms(drawn, kept));
    report["pose_sampling"] = {{"drawn", drawn.size()},
                               {"kept", kept.size()},
                               {"rejected", tally.rejected},
                               {"rejection_rate", 1.0 - static_cast<double>(kept.size()) / drawn.size()},
                               {"mean_seconds_per_simulation", survivors.empty() ? 0.0 : seconds / survivors.size()},
                               {"max_penetration_mm_kept", 1e3 * tally.maxPenetration}};
  });
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2);
    const nlohmann::json& poses = report["pose_sampling"];
    text << poses["kept"].get<int>() << " of " << poses["drawn"].get<int>() << " kept (rejection rate "
         << poses["rejection_rate"].get<double>() << "; rejected by reason " << poses["rejected"].dump() << "); "
         << poses["mean_seconds_per_simulation"].get<double>()
         << " s per simulation on one core; deepest kept vertex inside its body part "
         << poses["max_penetration_mm_kept"].get<double>() << " mm";
    section("Pose sampling and simulation filtering",
            std::to_string(args.filterPoses) +
                " poses from the appendix sampler (grey), each pruned when an arm falls inside the torso or else "
                "simulated on the T-shirt and kept only when it passes the paper's test (no triangle shrinks by more "
                "than 75% or grows by more than 100%) and no vertex ends more than 2 mm inside its body part (blue): " +
                text.str() + ".",
            {"poses/joint_histograms.png"});
  }

  report["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeJson(out / "report.json", report);
  writeIndex(out, report);
  PIXELCLOTH_INFO("demo: report written to " << (out / "index.html").string() << " in "
                                             << formatDuration(report["total_seconds"].get<double>()));
}
}  // namespace

void registerDemo(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* verb = app.add_subcommand("demo",
                                      "Run everything that exists on the built-in body and garments; write "
                                      "a report folder with pictures");
  verb->add_option("--out", args->out, "Report folder (index.html, report.json, pictures, meshes)")->required();
  verb->add_option("--poses", args->poses, "Number of random poses to show")
      ->capture_default_str()
      ->check(CLI::Range(1, 200));
  verb->add_option("--filter-poses", args->filterPoses,
                   "Poses drawn and simulated on the T-shirt for the filtering histograms (the issue asks for 200)")
      ->capture_default_str()
      ->check(CLI::Range(2, 2000));
  verb->add_option("--tshirt-samples", args->tshirtSamples,
                   "Simulated T-shirt samples (80% train the spline's length model, 10% test the reconstruction)")
      ->capture_default_str()
      ->check(CLI::Range(1, 2000));
  verb->add_option("--seed", args->seed, "Seed of the random poses")->capture_default_str();
  verb->callback([args] { runDemo(*args); });
}

}  // namespace pixelcloth::apps
