// pixelcloth markers and reconstruct: the markers, dataset and base forms; bad input refused, nothing written.
#include "cli_fixtures.h"

namespace pixelcloth::apps {
namespace {

// ---------------------------------------------------------------------------------------------------------------------
// markers and reconstruct (DESIGN.md, "Key-point-to-cage spline solver")

TEST_F(CliReconstructTest, DatasetFormWritesMetricsForEveryMethodAndTheSplineBeatsLinear) {
  const fs::path out = work_ / "rec";
  const CliRun run = runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--spacing", "0.08",
                                    "--out", out.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(noTemporaries(out));
  const nlohmann::json metrics = nlohmann::json::parse(readFile(out / "metrics.json"));
  EXPECT_EQ(metrics["samples"], 3);
  for (const char* method : {"linear", "catmull_rom", "spline", "spline_anisotropic"}) {
    SCOPED_TRACE(method);
    ASSERT_TRUE(metrics["methods"].contains(method)) << metrics.dump(2);
    const double cage = metrics["methods"][method]["cage_cm"], garment = metrics["methods"][method]["garment_cm"];
    EXPECT_TRUE(std::isfinite(cage) && std::isfinite(garment));
    EXPECT_GE(cage, 0);
    EXPECT_LT(garment, 1.0) << "a bent tie rebuilt from markers 8 cm apart";
    EXPECT_TRUE(metrics["methods"][method]["curves"].contains("outline"));
    EXPECT_GE(metrics["methods"][method]["pushed_out_percent"].get<double>(), 0);
  }
  EXPECT_LT(metrics["methods"]["spline"]["cage_cm"].get<double>(),
            metrics["methods"]["linear"]["cage_cm"].get<double>());
  EXPECT_TRUE(isPng(out / "error_maps.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "markers.json"));
  // The spline's length model, fitted on the training split (these garments are bent without stretch: worn lengths
  // near the rest lengths).
  ASSERT_TRUE(metrics["length_model"].is_object()) << metrics.dump(2);
  EXPECT_GT(metrics["length_model"]["samples"].get<int>(), 0);
  const nlohmann::json model = nlohmann::json::parse(readFile(out / "length_model.json"));
  EXPECT_EQ(model["garment"], "necktie");
  EXPECT_DOUBLE_EQ(model["marker_spacing_m"].get<double>(), 0.08);
  EXPECT_TRUE(model["curves"].contains("outline"));
  EXPECT_EQ(core::readMesh(out / "sample_000000" / "spline.obj").numVertices(), tie_.mesh.numVertices());
  EXPECT_TRUE(fs::is_regular_file(out / "sample_000000" / "truth.obj"));

  // Captured markers: noisy (fitted softly) and with a third of the curve markers missing; still solved.
  const CliRun noisy =
      runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--noise", "0.3", "--dropout", "0.3",
                     "--seed", "2", "--out", (work_ / "noisy").string(), "--quiet"});
  ASSERT_EQ(noisy.status, 0) << noisy;
  const nlohmann::json captured = nlohmann::json::parse(readFile(work_ / "noisy" / "metrics.json"));
  EXPECT_DOUBLE_EQ(captured["noise_cm"].get<double>(), 0.3);
  EXPECT_LT(captured["methods"]["spline"]["garment_cm"].get<double>(), 2.0) << captured.dump(2);

  // The model from the first run serves another run at its spacing, and is refused at another.
  const CliRun reused = runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--spacing",
                                       "0.08", "--length-model", (out / "length_model.json").string(), "--out",
                                       (work_ / "reused").string(), "--quiet"});
  ASSERT_EQ(reused.status, 0) << reused;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(readFile(work_ / "reused" / "metrics.json"))["methods"]["spline"]["cage_cm"],
                   metrics["methods"]["spline"]["cage_cm"].get<double>());
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--length-model",
                                     (out / "length_model.json").string(), "--out", (work_ / "spacing").string()}),
                      {"length_model.json", "0.08 m apart"}));
  EXPECT_TRUE(filesUnder(work_ / "spacing").empty());
}

TEST_F(CliReconstructTest, MarkersFormRebuildsOneSampleFromItsMarkers) {
  const fs::path markers = work_ / "m.json", pose = work_ / "pose.json", obj = work_ / "tie.obj";
  CliRun run = runPixelcloth({"markers", "--dataset", data_.string(), "--sample", "1", "--pose-out", pose.string(),
                              "--out", markers.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json set = nlohmann::json::parse(readFile(markers));
  EXPECT_EQ(set["garment"], "necktie");
  EXPECT_GT(set["markers"].size(), 8u);
  run = runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(), "--dressing",
                       (work_ / "dressing").string(), "--out", obj.string()});
  ASSERT_EQ(run.status, 0) << run;
  const core::Mesh rebuilt = core::readMesh(obj), truth = core::readMesh(work_ / "bent" / "tie_1.obj");
  ASSERT_EQ(rebuilt.numVertices(), truth.numVertices());
  EXPECT_LT((rebuilt.V - truth.V).rowwise().norm().mean(), 0.01);
  EXPECT_TRUE(rebuilt.hasUV());

  // With the length model a dataset run fitted (markers at the default spacing, as `markers` placed them).
  run = runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "all", "--meshes", "0", "--out",
                       (work_ / "fit").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  const fs::path withModel = work_ / "tie_model.obj";
  run = runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(), "--dressing",
                       (work_ / "dressing").string(), "--length-model", (work_ / "fit" / "length_model.json").string(),
                       "--out", withModel.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_LT((core::readMesh(withModel).V - truth.V).rowwise().norm().mean(), 0.01);
}

TEST_F(CliReconstructTest, WriteBaseFormWritesABaseFolderOfEveryRow) {
  const fs::path out = work_ / "bases";
  const CliRun run = runPixelcloth(
      {"reconstruct", "--dataset", data_.string(), "--write-base", out.string(), "--spacing", "0.08", "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(lines(run.out).size(), 1u) << run;
  EXPECT_NE(run.out.find(out.string()), std::string::npos) << run;
  EXPECT_NE(run.out.find("3 samples"), std::string::npos) << run;
  EXPECT_TRUE(run.err.empty()) << run;
  EXPECT_TRUE(noTemporaries(out));
  const data::BaseSet base = data::openBaseSet(out, data::readDatasetInfo(data_));
  EXPECT_EQ(base.samples, 3);
  EXPECT_EQ(base.vertices, tie_.mesh.numVertices());
  EXPECT_GT(base.markers, 8);
  EXPECT_TRUE(base.offsets.allFinite());
  EXPECT_GT(base.offsets.cwiseAbs().maxCoeff(), 0);
  EXPECT_DOUBLE_EQ(base.manifest["settings"]["marker_spacing_m"].get<double>(), 0.08);
  EXPECT_EQ(base.manifest["settings"]["method"], "spline_anisotropic");
}

TEST_F(CliReconstructTest, WriteBaseRefusesOptionsThatMeanNothingThere) {
  const std::string out = (work_ / "bases").string();
  EXPECT_TRUE(
      refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", out, "--split", "test"}),
              {"--split", "all splits"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", out, "--out",
                                     (work_ / "rec").string()}),
                      {"--write-base", "--out"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", out, "--method", "linear"}),
              {"--method"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--markers", (work_ / "m.json").string(), "--pose",
                                     (work_ / "p.json").string(), "--write-base", out}),
                      {"--write-base", "--dataset"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string()}), {"--out", "--write-base"}));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--write-base", data_.string()}),
                      {"holds a dataset (manifest.json); a base folder goes in a folder of its own"}));
  EXPECT_TRUE(filesUnder(out).empty());
  EXPECT_FALSE(fs::exists(work_ / "rec"));
  EXPECT_EQ(runPixelcloth({"dataset", "check", data_.string()}).status, 0);
}

TEST_F(CliReconstructTest, RefusesBadInputsNamingTheFileAndWritesNothing) {
  const fs::path markers = work_ / "m.json", pose = work_ / "pose.json";
  ASSERT_EQ(runPixelcloth({"markers", "--dataset", data_.string(), "--sample", "0", "--pose-out", pose.string(),
                           "--out", markers.string()})
                .status,
            0);
  const std::string dressing = (work_ / "dressing").string();
  auto reconstruct = [&](const fs::path& m, const fs::path& out) {
    return runPixelcloth({"reconstruct", "--markers", m.string(), "--pose", pose.string(), "--dressing", dressing,
                          "--out", out.string()});
  };
  EXPECT_TRUE(refused(reconstruct(work_ / "missing.json", work_ / "a.obj"), {"missing.json"}));
  EXPECT_FALSE(fs::exists(work_ / "a.obj"));

  nlohmann::json set = nlohmann::json::parse(readFile(markers));
  nlohmann::json edited = set;
  for (auto& m : edited["markers"])
    if (m.contains("curve")) {
      m["curve"] = "collar";
      break;
    }
  writeFile(work_ / "curve.json", edited.dump());
  EXPECT_TRUE(refused(reconstruct(work_ / "curve.json", work_ / "b.obj"), {"curve.json", "collar"}));
  EXPECT_FALSE(fs::exists(work_ / "b.obj"));

  std::string text = set.dump();
  const size_t at = text.find("\"position\":[");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 12, "NaN,");
  writeFile(work_ / "nan.json", text);
  EXPECT_TRUE(refused(reconstruct(work_ / "nan.json", work_ / "c.obj"), {"nan.json"}));
  EXPECT_FALSE(fs::exists(work_ / "c.obj"));

  edited = set;
  edited["garment"] = "skirt";
  writeFile(work_ / "skirt.json", edited.dump());
  EXPECT_TRUE(refused(reconstruct(work_ / "skirt.json", work_ / "d.obj"), {"skirt.json", "skirt"}));
  EXPECT_FALSE(fs::exists(work_ / "d.obj"));

  // A length model that is cut short, or for another garment.
  auto withModel = [&](const fs::path& model, const fs::path& out) {
    return runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(), "--dressing", dressing,
                          "--length-model", model.string(), "--out", out.string()});
  };
  writeFile(work_ / "cut_model.json", R"({"format": "pixelcloth.length_model", "garment": "necktie", "cur)");
  EXPECT_TRUE(refused(withModel(work_ / "cut_model.json", work_ / "f.obj"), {"cut_model.json"}));
  writeFile(work_ / "shirt_model.json",
            R"({"format": "pixelcloth.length_model", "garment": "tshirt", "marker_spacing_m": 0.1,
                "smoothing_passes": 2, "samples": 1, "curves": {"chest": {"intercept": 1, "slope": 0}}})");
  EXPECT_TRUE(refused(withModel(work_ / "shirt_model.json", work_ / "g.obj"), {"shirt_model.json", "tshirt"}));
  EXPECT_FALSE(fs::exists(work_ / "f.obj") || fs::exists(work_ / "g.obj"));

  // T-shirt markers for a necktie dressing: the embedding does not fit.
  ASSERT_EQ(runPixelcloth({"markers", "--garment", "tshirt", "--out", (work_ / "shirt_def.json").string()}).status, 0);
  EXPECT_TRUE(refused(reconstruct(work_ / "shirt_def.json", work_ / "e.obj"), {"shirt_def.json", "no position"}));
  EXPECT_FALSE(fs::exists(work_ / "e.obj"));

  // Dataset form: an unknown split, a folder that is not a dataset, a clearance of a metre.
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--body-clearance", "1", "--out",
                                     (work_ / "r3").string()}),
                      {"clearance"}));
  EXPECT_TRUE(filesUnder(work_ / "r3").empty());
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--dataset", data_.string(), "--split", "validation", "--out",
                                     (work_ / "r1").string()}),
                      {"validation"}));
  EXPECT_TRUE(refused(
      runPixelcloth({"reconstruct", "--dataset", (work_ / "nowhere").string(), "--out", (work_ / "r2").string()}),
      {"nowhere"}));
  EXPECT_TRUE(filesUnder(work_ / "r1").empty());
  EXPECT_TRUE(filesUnder(work_ / "r2").empty());
}

TEST_F(CliReconstructTest, MarkersFarFromTheBodyOrOfAnotherGarmentAreRefused) {
  const fs::path markers = work_ / "m.json", pose = work_ / "pose.json";
  ASSERT_EQ(runPixelcloth({"markers", "--dataset", data_.string(), "--sample", "1", "--pose-out", pose.string(),
                           "--out", markers.string()})
                .status,
            0);
  nlohmann::json set = nlohmann::json::parse(readFile(markers));
  const std::string name = set["markers"][2]["name"];
  set["markers"][2]["position"] = {1e30, 0, 0};
  writeFile(work_ / "far.json", set.dump());
  EXPECT_TRUE(refused(
      runPixelcloth({"reconstruct", "--markers", (work_ / "far.json").string(), "--pose", pose.string(), "--dressing",
                     (work_ / "dressing").string(), "--out", (work_ / "far.obj").string()}),
      {"far.json", "marker '" + name + "' is 1e+30 m from where its garment vertex rests", "expected within 1 m"}));
  EXPECT_FALSE(fs::exists(work_ / "far.obj"));

  // The necktie's markers with a T-shirt's dressing folder.
  const fs::path shirtDressing = work_ / "shirt_dressing";
  fs::create_directories(shirtDressing);
  fs::copy(body_, shirtDressing / "body", fs::copy_options::recursive);
  const core::Mesh body = core::readMesh(body_ / "body.obj");
  const garment::Garment shirt = garment::makeTShirt();
  const Eigen::MatrixX3d u = Eigen::RowVector3d(1, 0, 0).replicate(shirt.mesh.numVertices(), 1);
  garment::saveEmbedding(shirtDressing, garment::embedClosest(body.V, body.F, shirt.mesh.V, u));
  core::writeNpy(shirtDressing / "rest_positions.npy", Eigen::MatrixXd(shirt.mesh.V));
  EXPECT_TRUE(refused(runPixelcloth({"reconstruct", "--markers", markers.string(), "--pose", pose.string(),
                                     "--dressing", shirtDressing.string(), "--out", (work_ / "mixed.obj").string()}),
                      {"rest_positions.npy", "m.json", "necktie", "the garments differ"}));
  EXPECT_FALSE(fs::exists(work_ / "mixed.obj"));
}

}  // namespace
}  // namespace pixelcloth::apps
