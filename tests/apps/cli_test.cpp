// The program as a whole: verbs, help, the options every verb shares, and the demo and bench verbs end to end.
#include "cli_fixtures.h"

namespace pixelcloth::apps {
namespace {

// ---------------------------------------------------------------------------------------------------------------------
// The command line itself

TEST_F(CliTest, NoVerbExitsTwo) {
  CliRun run = runPixelcloth({});
  EXPECT_EQ(run.status, 2) << run;
  EXPECT_NE((run.out + run.err).find("subcommand"), std::string::npos) << run;
}

TEST_F(CliTest, UnknownVerbExitsTwo) {
  EXPECT_TRUE(refused(runPixelcloth({"drape"}), {"unknown verb 'drape'", "generate", "view"}));
  EXPECT_TRUE(refused(runPixelcloth({"-q", "--no-verify", "drape", "--out", "x"}), {"unknown verb 'drape'"}));
}

TEST_F(CliTest, HelpOfEveryVerbListsItsOptions) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> verbs = {
      {"body", {"--out", "--shape", "--corrupt-weights", "--corrupt-fraction", "--import", "--joints"}},
      {"garment", {"kind", "tshirt", "necktie", "--out", "--vertices"}},
      {"pose", {"--body", "--pose", "--random", "--seed", "--out"}},
      {"demo", {"--out", "--poses", "--seed"}},
      {"bench", {"--repeats", "--probe-friction"}},
      {"bases", {"--figures", "--side", "--cells", "--amplitude", "--theta", "--ratio", "--size"}},
      {"images",
       {"--garment", "--values", "--image", "--out", "--width", "--height", "--padding", "default", "--dataset",
        "--samples", "--all"}},
      {"dataset", {"info", "check", "merge", "import", "rebase"}},
      {"edit",
       {"--image", "--out", "--shift", "--inflate", "--inflate-add", "--brush", "--blend", "--mask", "--region",
        "default"}},
      {"cage", {"--garment", "tshirt", "--out", "--size"}},
      {"dress", {"--garment", "tshirt", "necktie", "--body", "--out"}},
      {"generate",
       {"--count", "--seed", "--out", "--garment", "--shard", "--body", "--body-shape", "--corrupt-weights", "--solver",
        "newton", "--step-degrees", "--friction", "--threads", "--quiet"}},
      {"markers", {"--garment", "--spacing", "--dataset", "--sample", "--noise", "--dropout", "--pose-out", "--out"}},
      {"reconstruct",
       {"--markers", "--pose", "--body", "--dressing", "--method", "--dataset", "--split", "--noise", "--dropout",
        "--spacing", "--rest-lengths", "--out", "--write-base", "--threads", "--quiet"}},
      {"model", {"--arch", "--width", "--inputs", "--garment", "--values", "--components", "--summary"}},
      {"train",
       {"--dataset", "--model", "--patches", "--width", "--components", "--space", "--residual", "--loss",
        "--normal-weight", "--edge-weight", "--epochs", "--batch", "--lr", "--seed", "--threads", "--out", "--quiet"}},
      {"predict", {"--model", "--pose", "--markers", "--dataset", "--samples", "--base", "--out"}},
      {"evaluate", {"--model", "--dataset", "--split", "--base", "--out"}},
      {"experiments", {"--scale", "small", "full", "--out", "--friction", "--threads"}},
      {"view", {"folder", "--out", "--max-scenes"}},
  };
  for (const auto& [verb, options] : verbs) {
    SCOPED_TRACE(verb);
    CliRun run = runPixelcloth({verb, "--help"});
    EXPECT_EQ(run.status, 0) << run;
    for (const std::string& option : options) EXPECT_NE(run.out.find(option), std::string::npos) << option << run;
  }
  CliRun top = runPixelcloth({"--help"});
  EXPECT_EQ(top.status, 0) << top;
  for (const auto& [verb, options] : verbs) EXPECT_NE(top.out.find(verb), std::string::npos) << verb << top;
}

TEST_F(CliTest, NegativeSeedsAreRefusedInEveryVerb) {
  const fs::path work = dir("work");
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--random", "1", "--seed", "-1", "--body", (work / "b").string(), "--out",
                                     (work / "p").string()}),
                      {"--seed", "a seed is a whole number of 0 or more, got -1"}));
  EXPECT_TRUE(refused(runPixelcloth({"generate", "--count", "2", "--seed", "-5", "--out", (work / "d").string()}),
                      {"--seed", "got -5"}));
  EXPECT_TRUE(refused(
      runPixelcloth({"generate", "--count", "2", "--seed", "18446744073709551616", "--out", (work / "d").string()}),
      {"--seed", "at most 18446744073709551615", "got 18446744073709551616"}));
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "import", "--garment", "necktie", "--objs", work.string(), "--poses",
                                     (work / "p.csv").string(), "--dressing", work.string(), "--seed", "-2", "--out",
                                     (work / "i").string()}),
                      {"--seed", "got -2"}));
  EXPECT_TRUE(filesUnder(work).empty()) << listing(filesUnder(work));
}

// ---------------------------------------------------------------------------------------------------------------------
// bench and demo

// The stitch group (two PCA fits at full size, two minutes) shares the procedural and learned groups' printing and is
// left out here.
TEST_F(CliTest, BenchPrintsOnlyJsonLines) {
  for (const char* group : {"procedural", "learn"}) {
    CliRun run = runPixelcloth({"bench", "--repeats", "1", "--epoch-shirts", "10", "--only", group});
    ASSERT_EQ(run.status, 0) << run;
    int figures = 0;
    for (const std::string& line : lines(run.out)) {
      SCOPED_TRACE(line);
      nlohmann::json figure = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
      ASSERT_TRUE(figure.is_object()) << "not a JSON object";
      for (const char* key : {"name", "value", "unit", "goal"}) EXPECT_TRUE(figure.contains(key)) << key;
      EXPECT_TRUE(figure["name"].is_string());
      EXPECT_TRUE(figure["value"].is_number());
      EXPECT_TRUE(figure["unit"].is_string());
      EXPECT_TRUE(figure["goal"].is_number());
      ++figures;
    }
    EXPECT_GT(figures, 0) << run;
  }
}

TEST_F(CliTest, DemoWritesReportWhosePicturesExist) {
  fs::path out = dir("out") / "report";
  CliRun run = runPixelcloth({"demo", "--out", out.string(), "--poses", "2", "--filter-poses", "16", "--tshirt-samples",
                              "10", "--own-garment-samples", "8", "--equilibrium-samples", "2"});
  ASSERT_EQ(run.status, 0) << run;
  ASSERT_TRUE(fs::is_regular_file(out / "index.html")) << listing(filesUnder(out));
  EXPECT_NO_THROW(nlohmann::json::parse(readFile(out / "report.json")));
  const std::string html = readFile(out / "index.html");
  const std::regex img(R"(<img[^>]*\ssrc\s*=\s*['"]([^'"]+)['"])", std::regex::icase);
  int pictures = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator(); ++it) {
    const std::string src = (*it)[1].str();
    EXPECT_TRUE(isPng(out / src)) << "index.html shows " << src;
    ++pictures;
  }
  EXPECT_GT(pictures, 0) << "index.html shows no pictures";
  EXPECT_TRUE(noTemporaries(out));
  // The imported T-shirt OBJ went through the pipeline as a garment folder, and its dataset carries it.
  EXPECT_NE(html.find("Your own garment"), std::string::npos);
  EXPECT_TRUE(isPng(out / "own_garment" / "predictions.png"));
  EXPECT_EQ(nlohmann::json::parse(readFile(out / "own_garment" / "dataset" / "manifest.json"))["garment"], "my_shirt");
  // Fitted to the body: it carries the template's cage lines, and a decoder per patch was trained on it.
  const nlohmann::json fitted = nlohmann::json::parse(readFile(out / "own_garment" / "garment" / "garment.json"));
  EXPECT_GE(fitted.at("cage_lines").size(), 10u);
  EXPECT_TRUE(fs::is_regular_file(out / "own_garment" / "model_patch" / "patch_00" / "model.json"))
      << listing(filesUnder(out / "own_garment" / "model_patch"));
  // The first poses at static equilibrium, beside projective dynamics' samples of them.
  EXPECT_NE(html.find("Static equilibrium"), std::string::npos);
  const nlohmann::json equilibrium = nlohmann::json::parse(readFile(out / "report.json"))["equilibrium"];
  EXPECT_EQ(equilibrium["samples"], 2);
  EXPECT_LT(equilibrium["stats"]["max_residual_force_ratio"].get<double>(), 0.01);
  EXPECT_EQ(nlohmann::json::parse(readFile(out / "dataset_tshirt_newton" / "manifest.json"))["settings"]["solver"],
            "newton");
  if (equilibrium["pairs"].get<int>() > 0) {
    EXPECT_GT(equilibrium["mean_distance_cm"].get<double>(), 0);
    EXPECT_TRUE(isPng(out / "dataset_tshirt_newton" / "against_projective.png"));
  }
  // The demo's own motion went out as a GLB, came back in through assimp unchanged, and was predicted frame by frame.
  EXPECT_NE(html.find("Motion"), std::string::npos);
  for (const char* file : {"motion/clip.glb", "motion/imported/poses.npy", "motion/predicted/animation.glb",
                           "motion/predicted/garment.pc2", "motion/predicted/body.pc2", "motion/predicted/metrics.json"})
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  const nlohmann::json motion = nlohmann::json::parse(readFile(out / "report.json"))["motion"];
  EXPECT_EQ(motion["joint_map"], "pixelcloth");
  EXPECT_LT(motion["max_retarget_error_deg"].get<double>(), 0.01);
  EXPECT_GT(motion["metrics"]["garment_jitter_cm"]["mean"].get<double>(), 0);

  // The 3D viewer of the report, linked from the top of index.html: the datasets, the learned models' predictions,
  // the reconstructions and both sequences (the page itself is opened in Chromium by ViewCli's tests).
  EXPECT_NE(html.find("href='view/index.html'"), std::string::npos);
  for (const char* file : {"view/index.html", "view/viewer.js", "view/site.js", "view/three/three.min.js",
                           "learning/model_patch/predictions.npy", "learning/model_residual_patch/metrics.json"})
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  const nlohmann::json groups = nlohmann::json::parse(readFile(out / "report.json"))["viewer"]["groups"];
  for (const char* group : {"dataset_tshirt (dataset)", "learning/model_patch (evaluation)",
                            "learning/model_residual_patch (evaluation)", "reconstruction (reconstruction)",
                            "motion/predicted (sequence)", "motion/reconstructed (sequence)"})
    EXPECT_TRUE(groups.contains(group)) << group << " in " << groups.dump();

  // Run again into the same folder, as a user does after pulling: the datasets are made afresh, so the models the first
  // run left were trained on other samples; the demo retrains them instead of refusing to resume.
  run = runPixelcloth({"demo", "--out", out.string(), "--poses", "2", "--filter-poses", "16", "--tshirt-samples", "10",
                       "--own-garment-samples", "8", "--equilibrium-samples", "2"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(noTemporaries(out));
}

}  // namespace
}  // namespace pixelcloth::apps
