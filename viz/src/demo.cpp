// The demo's sections: everything that exists, end to end, on the built-in body and garments.
#include "pixelcloth/viz/demo.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/data/face_statistics.h"
#include "pixelcloth/eval/demo.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/learn/model.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/patches/cloth_image.h"
#include "pixelcloth/patches/edit.h"
#include "pixelcloth/patches/garment_fill.h"
#include "pixelcloth/recon/reconstruct.h"
#include "pixelcloth/sim/pose_sampler.h"
#include "pixelcloth/viz/basis_figures.h"
#include "pixelcloth/viz/draw.h"
#include "pixelcloth/viz/pictures.h"
#include "pixelcloth/viz/pose_figures.h"
#include "pixelcloth/viz/previews.h"
#include "pixelcloth/viz/render.h"

namespace pixelcloth::viz {

namespace fs = std::filesystem;
using namespace core;
using namespace body;
using namespace garment;

namespace {
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

/// A simulated dataset's contact sheet (posed body, draped garment, cloth image of its first samples) and figures.
void drawDataset(Report& report, const body::Body& body, const std::string& name, const eval::SimulatedDataset& made) {
  const std::string folder = "dataset_" + name;
  const data::Dataset dataset = data::openDataset(made.folder);
  const Garment garment = data::datasetGarment(dataset.info);
  patches::ClothImager imager(garment);
  PreviewOptions preview;
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
    row.push_back(renderClothImage(imager.rasterize(dataset.offsetsOf(r)), preview));
  }
  writePng(made.folder / "contact_sheet.png", contactSheet(row, 3));
  report.json()[folder] = {{"samples", dataset.rows()},
                           {"seconds", made.seconds},
                           {"check", made.check.summary()},
                           {"stats", dataset.info.stats.toJson()}};
}
}  // namespace

body::Body demoBody(Report& report) {
  Body body;
  report.step("body: built-in mannequin, skeleton, bone-heat weights, parts", [&] {
    body = makeMannequin();
    saveBody(report.folder() / "body", body, "built-in mannequin (demo)");
    writePng(report.folder() / "body" / "body.png", renderBodySheet(body));
    report.json()["body"] = {{"vertices", body.mesh.numVertices()},
                             {"faces", body.mesh.numFaces()},
                             {"joints", body.skeleton.numJoints()},
                             {"height_m", body.mesh.V.col(1).maxCoeff()},
                             {"volume_m3", enclosedVolume(body.mesh.V, body.mesh.F)}};
  });
  report.section("Body",
                 "The built-in mannequin (" + std::to_string(body.mesh.numVertices()) +
                     " vertices, closed and manifold): shaded with its skeleton; bone-heat skin weights (a colour "
                     "per joint); collision parts (left arm red, right arm blue, torso grey, overlaps purple); side.",
                 {"body/body.png"});

  return body;
}

void demoBodyCage(Report& report, const body::Body& body) {
  report.step("body cage: loops, centre and side lines, armholes", [&] {
    cage::Cage bodyCage = cage::bodyCage(body);
    writeJson(report.folder() / "body" / "cage.json", cage::toJson(bodyCage));
    writePng(report.folder() / "body" / "cage.png", renderCageOnMesh(body.mesh, bodyCage));
    report.json()["body_cage"] = {{"curves", bodyCage.curves.size()}, {"nodes", bodyCage.nodes.size()}};
  });
  report.section("Body cage",
                 "The cage on the mannequin, where the T-shirt's seams and loops will sit: chest, waist, hem, "
                 "bicep and sleeve-hem loops (red / black), centre lines (blue), side, shoulder and armhole "
                 "lines (green); yellow dots are junctions, named like the shirt's.",
                 {"body/cage.png"});
}

void demoShapes(Report& report, const body::Body& body) {
  report.step("body shapes: thinner (-1), default (0), thicker (2)", [&] {
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
      report.json()["shapes"].push_back(
          {{"shape", shape}, {"volume_m3", enclosedVolume(shaped.mesh.V, shaped.mesh.F)}});
    }
    writePng(report.folder() / "shapes.png", contactSheet(pictures, 3));
  });
  report.section("Body shapes",
                 "The shape parameter scales girth (-1 thinner, 0 default, 2 thicker), as the paper's "
                 "intentionally modified body shapes.",
                 {"shapes.png"});
}

void demoSkinningArtifacts(Report& report, const body::Body& body) {
  report.step("skinning artifacts: corrupted upper-arm weights", [&] {
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
    writePng(report.folder() / "skinning_artifacts.png", contactSheet(pictures, 3));
  });
  report.section("Skinning artifacts",
                 "One pose with the bone-heat weights, then with half of each upper arm's weight moved "
                 "to the torso, then to the torso and the opposite arm (the paper's experiment).",
                 {"skinning_artifacts.png"});
}

void demoPoses(Report& report, const body::Body& body, int count, std::uint64_t seed) {
  report.step("poses: random poses within the joint limits", [&] {
    sim::PoseSamplerOptions options;
    options.seed = seed;
    sim::PoseSampler sampler(body, options);
    std::vector<Pose> poses = sampler.sample(count);
    writePosedBodies(report.folder() / "poses", body, poses, {{"seed", seed}, {"sampler", "appendix"}});
    report.json()["poses"] = {{"kept", sampler.stats().accepted},
                              {"rejected_arm_inside_torso", sampler.stats().rejectedArmInsideTorso}};
  });
  report.section(
      "Posed bodies",
      "Poses from the paper's sampler (half-normal mixtures on the centre line; uniform azimuth, "
      "sine-altitude and twist for shoulders and arms, within the AAOS limits; poses with an arm inside the torso "
      "rejected), skinned by linear blend skinning; the skeleton is drawn over each.",
      {"poses/posed.png"});
}

void demoBodyImport(Report& report, const body::Body& body) {
  report.step("import: an A-posed body brought back to the T-pose", [&] {
    fs::path folder = report.folder() / "import";
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
    report.json()["import"] = {
        {"mean_vertex_distance_to_original_mm", 1000.0 * (imported.mesh.V - body.mesh.V).rowwise().norm().mean()}};
  });
  report.section("Body import",
                 "An A-posed copy of the mannequin written as OBJ + joints JSON, imported back: weights "
                 "recomputed, arms rotated into the T-pose (left: input; right: imported body).",
                 {"import/import.png"});
}

void demoGarments(Report& report, const body::Body& body) {
  report.step("garments: T-shirt and necktie sewing patterns", [&] {
    Garment shirt = makeTShirt();
    saveGarment(report.folder() / "tshirt", shirt);
    writePng(report.folder() / "tshirt" / "pattern.png", renderPattern(shirt));
    writePng(report.folder() / "tshirt" / "garment.png", renderGarmentOnBody(shirt, &body));
    Garment tie = makeNecktie();
    saveGarment(report.folder() / "necktie", tie);
    writePng(report.folder() / "necktie" / "pattern.png", renderPattern(tie));
    writePng(report.folder() / "necktie" / "garment.png", renderGarmentOnBody(tie, &body));
    report.json()["tshirt"] = {{"summary", shirt.summary()},
                               {"meshing", shirt.meshing.summary(shirt.mesh.numVertices())},
                               {"length_m", shirt.length()}};
    report.json()["necktie"] = {{"summary", tie.summary()}, {"meshing", tie.meshing.summary(tie.mesh.numVertices())}};
  });
  report.section("T-shirt pattern",
                 "Front and back layouts (front, back, sleeve halves), triangulated by CGAL's constrained "
                 "Delaunay mesher; seams in matching colours on both layouts, openings dark. " +
                     report.json()["tshirt"]["summary"].get<std::string>(),
                 {"tshirt/pattern.png", "tshirt/garment.png"});
  report.section("Necktie pattern", report.json()["necktie"]["summary"].get<std::string>(),
                 {"necktie/pattern.png", "necktie/garment.png"});
}

void demoCageAndPatches(Report& report) {
  report.step("cage and patches: T-shirt (28 patches) and necktie", [&] {
    writeCageFolder(makeTShirt(), report.folder() / "tshirt");
    writeCageFolder(makeNecktie(), report.folder() / "necktie");
  });
  report.section("Cage and patches",
                 "Each garment's cage: seams (dark red), body loops (blue), centre lines (green), "
                 "openings (black) and side-panel splits (orange); the T-shirt splits into 14 patches per "
                 "side, each within 128 px of its side's 512 x 512 image. Lists in tshirt/patches.json.",
                 {"tshirt/cage.png", "necktie/cage.png"});
}

void demoBases(Report& report) {
  report.step("patch bases: the appendix's figures", [&] { writeBasisFigures(report.folder() / "bases"); });
  report.section("Patch bases",
                 "Harmonic (left pair) and anisotropic (right pair, 30 degrees, ratio 0.1) fills of a 20 cm "
                 "square patch from four boundary shapes: one bump, two bumps, a sine wave, an S-shaped "
                 "boundary; height maps and shaded surfaces.",
                 {"bases/bases.png"});
}

void demoClothImages(Report& report) {
  report.step("cloth images: a cage-driven fill, rasterised, edited", [&] {
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
    patches::writeClothImage(report.folder() / "images" / "filled.exr", image);
    // Edits of the appendix: a dn brush on the chest, then a shift of the whole image.
    patches::ClothImage edited = image;
    patches::brushImage(edited, {0.5 * image.width, 0.45 * image.height, 0.09 * image.width, 0.03f});
    patches::shiftImage(edited, 0.003f, 0.0f);
    patches::writeClothImage(report.folder() / "images" / "edited.exr", edited);
    PreviewOptions preview;
    preview.range = 0.04f;
    writePng(report.folder() / "images" / "filled_and_edited.png",
             contactSheet({renderClothImage(image, preview), renderClothImage(edited, preview)}, 1));
    Eigen::MatrixXf back = imager.sample(image);
    report.json()["cloth_image"] = {{"size", {image.width, image.height}},
                                    {"round_trip_max_error_mm", 1e3 * (back - offsets).cwiseAbs().maxCoeff()}};
  });
  report.section("Cloth images",
                 "Offsets set on the T-shirt's cage only (a smooth wave), patch interiors filled by their "
                 "bases, rasterised to a 256 x 256 cloth image per side (RGB = du, dv, dn; padding dimmer). "
                 "Below: the same image edited with a dn brush on the chest and a shift in du. EXR files in "
                 "images/.",
                 {"images/filled_and_edited.png"});
}

void demoDressing(Report& report, const body::Body& body, const std::vector<eval::DressedGarment>& dressed) {
  for (const eval::DressedGarment& d : dressed) {
    writeDressingFolder(body, d.garment, d.dressing, report.folder() / "dressing" / d.garment.name);
    report.json()["dressing"][d.garment.name] = d.dressing.summary();
  }
  report.section(
      "Dressing",
      "The T-shirt's cage morphed onto the body cage, the rest carried by a Poisson solve, pushed out of the "
      "body and relaxed by edge-length equalisation on it: " +
          report.json()["dressing"]["tshirt"].get<std::string>() +
          ". Area distortion in pattern space before and after relaxation (red stretch, blue compression), "
          "and the dressed shirt. The necktie keeps its rest placement.",
      {"dressing/tshirt/area_distortion.png", "dressing/tshirt/dressed.png"});
}

void demoTShirtDataset(Report& report, const body::Body& body, const eval::SimulatedDataset& made) {
  drawDataset(report, body, "tshirt", made);
  // The appendix statistics: per face, area ratios and self-intersections over the samples (dataset stats).
  const data::Dataset dataset = data::openDataset(made.folder);
  const data::FaceStatistics faces = data::faceStatistics(dataset);
  writeFaceStatistics(data::datasetGarment(dataset.info), faces, made.folder, made.folder / "faces");
  const double everHit = (faces.selfIntersection.array() > 0).cast<double>().mean();
  report.json()["dataset_tshirt"]["faces"] = {{"min_area_ratio", faces.minAreaRatio.minCoeff()},
                                              {"max_area_ratio", faces.maxAreaRatio.maxCoeff()},
                                              {"samples_self_intersecting", faces.samplesSelfIntersecting},
                                              {"faces_ever_self_intersecting", everHit}};
  report.section(
      "Simulated T-shirt dataset",
      "pixelcloth generate: poses from the appendix sampler, the dressed shirt settled under gravity, then "
      "walked to each pose in steps of at most 25 degrees per joint, the cloth carried with the body and relaxed "
      "against it (with friction); checked by dataset check (" +
          report.json()["dataset_tshirt"]["check"].get<std::string>() +
          "); solver statistics and rejections: " + report.json()["dataset_tshirt"]["stats"].dump() +
          ". Each row: posed body, simulated shirt (front, three-quarter, back), its cloth image. Then the paper's "
          "appendix statistics (pixelcloth dataset stats): per face, the smallest and largest area ratio over the "
          "samples, and how often the face passes through the shirt itself (" +
          std::to_string(faces.samplesSelfIntersecting) + " of " + std::to_string(faces.samples) +
          " samples; neither solver has cloth self-collision).",
      {"dataset_tshirt/contact_sheet.png", "dataset_tshirt/faces/area_distortion.png",
       "dataset_tshirt/faces/self_intersection.png"});
}

void demoReconstruction(Report& report, const body::Body& body, const eval::DemoReconstruction& made) {
  {
    const data::Dataset dataset = data::openDataset(report.folder() / "dataset_tshirt");
    const fs::path folder = report.folder() / "reconstruction";
    const recon::DatasetReconstructionReport& rec = made.report;
    const Garment shirt = data::datasetGarment(dataset.info);
    writePng(folder / "error_maps.png", renderReconstructionErrors(shirt, rec));
    std::vector<RgbImage> rows;
    for (int r : made.shown) {
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
    report.json()["reconstruction"] = summary;
  }
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2);
    for (const auto& [name, m] : report.json()["reconstruction"]["methods"].items())
      text << name << ": cage " << m["cage_cm"].get<double>() << " cm, garment " << m["garment_cm"].get<double>()
           << " cm; ";
    report.section(
        "Reconstruction from markers",
        "pixelcloth reconstruct --dataset: markers at every cage junction and about every 10 cm along each curve (" +
            std::to_string(report.json()["reconstruction"]["markers"].get<int>()) +
            ") taken from each simulated shirt; each cage curve drawn through them linearly, by Catmull-Rom, or "
            "by the length-preserving spline, whose segments keep the worn lengths a model fitted on the training "
            "split predicts (reconstruction/length_model.json); patch interiors filled from the cage by the "
            "isotropic (or anisotropic) bases, then kept 1 mm out of the posed body. Mean per-vertex error over the " +
            std::to_string(report.json()["reconstruction"]["samples"].get<int>()) + " samples of the " +
            report.json()["reconstruction"]["split"].get<std::string>() + " split: " + text.str() +
            "Rows: ground truth, spline, linear (front, back). Below: mean per-vertex error in pattern space per "
            "method (reconstruction/metrics.json has per-curve length errors).",
        {"reconstruction/comparison.png", "reconstruction/error_maps.png"});
  }
}

void demoNecktieDataset(Report& report, const body::Body& body, const eval::SimulatedDataset& made) {
  drawDataset(report, body, "necktie", made);
  report.section(
      "Simulated necktie dataset",
      "pixelcloth generate --garment necktie: poses from the appendix sampler (centre line only), quasistatic "
      "drape with the knot held at the collar; checked by dataset check (" +
          report.json()["dataset_necktie"]["check"].get<std::string>() +
          "). Each row: posed body, simulated necktie, its cloth image (du dv dn).",
      {"dataset_necktie/contact_sheet.png"});
}

void demoPoseSampling(Report& report, const eval::PoseFiltering& filtering) {
  {
    const std::vector<Pose>&drawn = filtering.drawn, &survivors = filtering.simulated, &kept = filtering.kept;
    const data::DatasetStats& tally = filtering.tally;
    const double seconds = filtering.seconds;
    writePng(report.folder() / "poses" / "joint_histograms.png",
             renderJointHistograms({{"drawn", drawn, {175, 175, 175}},
                                    {"simulated (after pruning arms in the torso)", survivors, {140, 185, 235}},
                                    {"kept (area test, penetration)", kept, {30, 80, 190}}}));
    auto bin = [](const JointBinLoss& loss) {
      return nlohmann::json{{"joint", loss.joint},          {"axis", loss.axis},  {"lower_degrees", loss.lowerDegrees},
                            {"upper_degrees", loss.upperDegrees}, {"before", loss.before}, {"after", loss.after},
                            {"kept_fraction", loss.keptFraction()}};
    };
    report.json()["pose_sampling"] = {
        {"worst_bin_simulation", bin(worstJointBin(survivors, kept))},
        {"worst_bin_overall", bin(worstJointBin(drawn, kept))},
        {"drawn", drawn.size()},
        {"kept", kept.size()},
        {"kept_after_extra_rounds", tally.acceptedAfterExtra},
        {"rejected", tally.rejected},
        {"rejection_rate", 1.0 - static_cast<double>(kept.size()) / drawn.size()},
        {"mean_seconds_per_simulation", survivors.empty() ? 0.0 : seconds / survivors.size()},
        {"max_penetration_mm_kept", 1e3 * tally.maxPenetration}};
  }
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2);
    const nlohmann::json& poses = report.json()["pose_sampling"];
    text << poses["kept"].get<int>() << " of " << poses["drawn"].get<int>() << " kept, "
         << poses["kept_after_extra_rounds"].get<int>()
         << " of them only after relaxing past the scheduled iterations at the target pose (rejection rate "
         << poses["rejection_rate"].get<double>() << "; rejected by reason " << poses["rejected"].dump() << "); "
         << poses["mean_seconds_per_simulation"].get<double>()
         << " s per simulation on one core; deepest kept vertex inside its body part "
         << poses["max_penetration_mm_kept"].get<double>() << " mm";
    auto describe = [&](const nlohmann::json& bin, const char* stage) {
      text << "; the joint-angle bin (of those with at least 10 poses) that loses most " << stage << " is "
           << bin["joint"].get<std::string>() << " " << bin["axis"].get<std::string>() << " in ["
           << bin["lower_degrees"].get<double>() << ", " << bin["upper_degrees"].get<double>() << "] degrees, "
           << bin["after"].get<int>() << " of " << bin["before"].get<int>() << " kept";
    };
    describe(poses["worst_bin_simulation"], "to simulation");
    describe(poses["worst_bin_overall"], "to pruning and simulation together");
    report.section(
        "Pose sampling and simulation filtering",
        std::to_string(filtering.drawn.size()) +
            " poses from the appendix sampler (grey), each pruned when an arm falls inside the torso or else "
            "simulated on the T-shirt (light blue) and kept only when it passes the paper's test (no triangle "
            "shrinks by more than 75% or grows by more than 100%) and no vertex ends more than 2 mm inside its body "
            "part (blue); bars are counts on one scale: " +
            text.str() + ".",
        {"poses/joint_histograms.png"});
  }
}

void demoNetworks(Report& report, const learn::TrainReport& necktie) {
  std::ostringstream text;
  text << std::fixed;
  report.step("networks: the paper's decoders and the fully connected baselines", [&] {
    const int values = 3 * makeTShirt().mesh.numVertices();
    for (learn::Architecture architecture :
         {learn::Architecture::Whole, learn::Architecture::Patch, learn::Architecture::Necktie,
          learn::Architecture::FullyConnected, learn::Architecture::FullyConnectedPca}) {
      for (double width : {1.0, 0.25}) {
        learn::ModelSpec spec;
        spec.architecture = architecture;
        spec.width = width;
        spec.outputValues = values;
        const learn::ModelSummary summary = learn::summarize(spec);
        nlohmann::json entry = summary.toJson();
        entry.erase("layers");
        if (width == 0.25) {
          // One forward pass of one sample (after a warm-up), inference mode, on this machine's cores.
          const learn::Model model(spec);
          const Eigen::MatrixXf pose = Eigen::MatrixXf::Zero(1, spec.inputs());
          model.forward(pose);
          const auto start = std::chrono::steady_clock::now();
          model.forward(pose);
          entry["forward_ms"] = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        report.json()["networks"].push_back(entry);
        text << learn::architectureName(architecture) << (width == 1.0 ? "" : " (width 0.25)") << ": "
             << std::setprecision(2) << summary.parameters / 1e6 << "M parameters, " << std::setprecision(3)
             << summary.gflopForward << " GFLOP; ";
      }
    }
  });
  // The quarter-width necktie decoder trained briefly on the demo's necktie samples.
  const learn::NetworkReport& trained = necktie.networks.front();
  writePng(necktie.networks.front().folder / "training.png", renderTrainingCurves(trained, "necktie width 0.25"));
  {
    const learn::EpochRecord& best = trained.epochs[trained.bestEpoch - 1];
    double seconds = 0;
    for (const learn::EpochRecord& e : trained.epochs) seconds += e.seconds;
    report.json()["training"] = {{"model", "necktie"},
                                 {"width", 0.25},
                                 {"epochs", trained.epochs.size()},
                                 {"samples", report.json()["dataset_necktie"]["samples"]},
                                 {"best_epoch", best.epoch},
                                 {"first_train_error_cm", trained.epochs.front().trainErrorCm},
                                 {"train_error_cm", best.trainErrorCm},
                                 {"seconds", seconds}};
  }
  report.section("Networks",
                 "The learned half begins with its networks (learn/). Per sample, the "
                 "whole-garment decoder maps the 90-float pose to a 256 x 256 x 6 cloth image of both sides, a patch "
                 "decoder to a 160 x 160 x 3 patch crop, the necktie decoder its 36 floats to a 64-wide, 256-tall "
                 "image of 3 channels; the "
                 "fully connected baselines map the pose to the T-shirt's per-vertex values, directly or through 128 "
                 "PCA coefficients: " +
                     text.str() + "the quarter-width forward times are in report.json (networks). Below: a " +
                     "quarter-width necktie decoder trained for " + std::to_string(trained.epochs.size()) +
                     " epochs on the demo's " + std::to_string(report.json()["dataset_necktie"]["samples"].get<int>()) +
                     " simulated neckties (masked L1, Adam; the best epoch chosen on the regularisation split): "
                     "per-vertex error on its training samples " +
                     [&] {
                       std::ostringstream t;
                       t << std::fixed << std::setprecision(2) << trained.epochs.front().trainErrorCm << " cm after "
                         << "the first epoch, " << trained.epochs[trained.bestEpoch - 1].trainErrorCm << " cm at the "
                         << "best, " << report.json()["training"]["seconds"].get<double>() << " s of training; "
                         << "the dataset has no test split, so this is no learned result: too few samples to "
                         << "generalise, it shows the training path works end to end.";
                       return t.str();
                     }(),
                 {"model_necktie/training.png"});
}

}  // namespace pixelcloth::viz
