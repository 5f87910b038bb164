// pixelcloth dataset and generate: import, info, check, stats, merge, images, rebase, simulation; bad input refused.
#include "cli_fixtures.h"

namespace pixelcloth::apps {
namespace {

// ---------------------------------------------------------------------------------------------------------------------

TEST_F(CliDatasetTest, ImportInfoCheckStatsMergeImages) {
  const fs::path data = work_ / "data";
  CliRun run = import(work_ / "objs", work_ / "poses.csv", data);
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(noTemporaries(data));
  EXPECT_FALSE(fs::exists(data / "partial"));

  run = runPixelcloth({"dataset", "check", data.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_TRUE(startsWith(run.out, "ok")) << run;

  run = runPixelcloth({"dataset", "info", data.string()});
  ASSERT_EQ(run.status, 0) << run;
  for (const char* text : {"necktie", "imported", "samples      3", "splits", "penetration", "rejected"})
    EXPECT_NE(run.out.find(text), std::string::npos) << text << run;
  run = runPixelcloth({"dataset", "info", "--json", data.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["rows"], 3);
  EXPECT_EQ(info["pose_size"], 36);
  EXPECT_TRUE(info["stats"].contains("max_penetration_mm"));
  EXPECT_EQ(info["counts"]["train"].get<int>() + info["counts"]["regularisation"].get<int>() +
                info["counts"]["test"].get<int>(),
            3);

  run = runPixelcloth({"dataset", "merge", "--out", (work_ / "merged").string(), data.string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(run.err, "") << "--quiet silences progress";
  EXPECT_EQ(readFile(work_ / "merged" / "offsets.npy"), readFile(data / "offsets.npy"));
  EXPECT_EQ(runPixelcloth({"dataset", "check", (work_ / "merged").string()}).status, 0);
  // The same poses in both: every sample matched, at no distance.
  run = runPixelcloth({"dataset", "compare", data.string(), (work_ / "merged").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.out.find("3 samples posed alike (of 3 and 3): mean distance 0 cm"), std::string::npos) << run;
  run = runPixelcloth({"dataset", "compare", "--json", data.string(), (work_ / "merged").string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(nlohmann::json::parse(run.out)["samples"].size(), 3u);
  EXPECT_TRUE(
      refused(runPixelcloth({"dataset", "compare", data.string(), (work_ / "objs").string()}), {"manifest.json"}));

  // The appendix statistics as pictures, and the numbers behind them.
  run = runPixelcloth({"dataset", "stats", data.string(), "--out", (work_ / "stats").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.out.find("face statistics of 3 samples"), std::string::npos) << run;
  EXPECT_TRUE(isPng(work_ / "stats" / "area_distortion.png"));
  EXPECT_TRUE(isPng(work_ / "stats" / "self_intersection.png"));
  const nlohmann::json faces = nlohmann::json::parse(readFile(work_ / "stats" / "face_statistics.json"));
  EXPECT_EQ(faces["samples"], 3);
  EXPECT_EQ(faces["min_area_ratio"].size(), static_cast<size_t>(tie_.mesh.numFaces()));
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "stats", (work_ / "objs").string(), "--out", (work_ / "s2").string()}),
                      {"manifest.json"}));
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "stats", data.string(), "--out", data.string()}),
                      {"holds a dataset", "face statistics"}));
  EXPECT_FALSE(fs::exists(work_ / "s2"));

  run = runPixelcloth({"images", "--dataset", data.string(), "--all", "--out", (work_ / "images").string(), "--quiet"});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_EQ(run.err, "") << "--quiet silences progress";
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(isPng(work_ / "images" / ("cloth_00000" + std::to_string(i) + ".png")));
    const core::ExrImage exr = core::readExr(work_ / "images" / ("cloth_00000" + std::to_string(i) + ".exr"));
    EXPECT_TRUE(exr.hasChannel("du") || exr.hasChannel("tie.du"));
  }
  EXPECT_TRUE(refused(
      runPixelcloth({"images", "--dataset", data.string(), "--samples", "7", "--out", (work_ / "more").string()}),
      {"--samples 7", "0 to 2"}));

  // A damaged copy: check and merge refuse it, naming the file.
  fs::copy(data, work_ / "damaged", fs::copy_options::recursive);
  std::string bytes = readFile(data / "positions.npy");
  bytes[bytes.size() - 8] ^= 0x01;  // a mantissa bit: the value stays finite (a NaN is refused even unverified)
  writeFile(work_ / "damaged" / "positions.npy", bytes);
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "check", (work_ / "damaged").string()}), {"positions.npy", "CRC-32"}));
  EXPECT_TRUE(
      refused(runPixelcloth({"dataset", "merge", "--out", (work_ / "merged2").string(), (work_ / "damaged").string()}),
              {"positions.npy", "CRC-32"}));
  EXPECT_FALSE(fs::exists(work_ / "merged2" / "manifest.json"));
}

TEST_F(CliDatasetTest, RebaseOntoABodyFolderAndRefuseADatasetAsTheBody) {
  const fs::path data = work_ / "data";
  ASSERT_EQ(import(work_ / "objs", work_ / "poses.csv", data).status, 0);
  const fs::path rebased = work_ / "rebased";
  CliRun run = runPixelcloth({"dataset", "rebase", data.string(), "--body", body_.string(), "--out", rebased.string()});
  ASSERT_EQ(run.status, 0) << run;
  EXPECT_NE(run.out.find("rebased 3 samples"), std::string::npos) << run;
  EXPECT_EQ(runPixelcloth({"dataset", "check", rebased.string()}).status, 0);
  EXPECT_EQ(readFile(rebased / "positions.npy"), readFile(data / "positions.npy"));
  const nlohmann::json manifest = nlohmann::json::parse(readFile(rebased / "manifest.json"));
  EXPECT_EQ(manifest["body"]["rebased_from"]["folder"], fs::absolute(data).lexically_normal().string());

  EXPECT_TRUE(refused(
      runPixelcloth({"dataset", "rebase", data.string(), "--body", data.string(), "--out", (work_ / "wrong").string()}),
      {"is a dataset folder", "body folder", (data / "body").string()}));
  EXPECT_FALSE(fs::exists(work_ / "wrong"));
}

TEST_F(CliDatasetTest, RefusesBadInputsNamingTheFile) {
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "check", (work_ / "nowhere").string()}), {"nowhere", "no such"}));
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "info", (work_ / "objs").string()}), {"manifest.json"}));
  EXPECT_TRUE(refused(
      runPixelcloth({"dataset", "merge", "--out", (work_ / "m").string(), (work_ / "nowhere").string()}), {"nowhere"}));

  // An OBJ of another vertex count.
  fs::copy(work_ / "objs", work_ / "objs_few", fs::copy_options::recursive);
  core::Mesh few;
  few.V = tie_.mesh.V.topRows(3);
  few.F.resize(1, 3);
  few.F << 0, 1, 2;
  core::writeMesh(work_ / "objs_few" / "tie_1.obj", few);
  EXPECT_TRUE(refused(import(work_ / "objs_few", work_ / "poses.csv", work_ / "out1"), {"tie_1.obj", "3 vertices"}));
  EXPECT_FALSE(fs::exists(work_ / "out1"));

  // A NaN coordinate in an OBJ.
  fs::copy(work_ / "objs", work_ / "objs_nan", fs::copy_options::recursive);
  std::string text = readFile(work_ / "objs_nan" / "tie_2.obj");
  const size_t v = text.find("\nv ");
  ASSERT_NE(v, std::string::npos);
  text.replace(v, 4, "\nv nan ");
  writeFile(work_ / "objs_nan" / "tie_2.obj", text);
  EXPECT_TRUE(refused(import(work_ / "objs_nan", work_ / "poses.csv", work_ / "out2"), {"tie_2.obj"}));
  EXPECT_FALSE(fs::exists(work_ / "out2"));

  // A pose CSV with a wrong column count, and fewer poses than frames.
  writeFile(work_ / "short.csv", "1,0,0,0,1,0,0,0,1\n");
  EXPECT_TRUE(refused(import(work_ / "objs", work_ / "short.csv", work_ / "out3"),
                      {"short.csv", "line 1", "9 columns, expected 36"}));
  std::string two = readFile(work_ / "poses.csv");
  two = two.substr(0, two.rfind('\n', two.size() - 2) + 1);
  writeFile(work_ / "two.csv", two);
  EXPECT_TRUE(refused(import(work_ / "objs", work_ / "two.csv", work_ / "out4"), {"two.csv", "2 poses for 3 OBJ"}));
  EXPECT_FALSE(fs::exists(work_ / "out4"));
}

TEST_F(CliBodyTest, GenerateMakesACheckedNecktieDatasetAndResumes) {
  const fs::path out = dir("generate_necktie");
  const fs::path data = out / "tie";
  const CliRun first = runPixelcloth({"generate", "--garment", "necktie", "--count", "3", "--seed", "5", "--body",
                                      body_.string(), "--out", data.string()});
  ASSERT_EQ(first.status, 0) << first;
  for (const char* name : {"manifest.json", "poses.npy", "positions.npy", "offsets.npy", "split.npy"})
    EXPECT_TRUE(fs::exists(data / name)) << name;
  const CliRun check = runPixelcloth({"dataset", "check", data.string()});
  EXPECT_EQ(check.status, 0) << check;
  EXPECT_NE(check.out.find("ok"), std::string::npos) << check;
  const nlohmann::json manifest = nlohmann::json::parse(readFile(data / "manifest.json"));
  EXPECT_EQ(manifest["pose_size"], 36);
  EXPECT_EQ(manifest["stats"]["accepted"], 3);
  EXPECT_LE(manifest["stats"]["max_penetration_mm"].get<double>(), 2.0);
  // A simulated dataset's statistics add the joint angles of the sampler's draws, made again from its seed.
  const CliRun stats = runPixelcloth({"dataset", "stats", data.string(), "--out", (out / "stats").string(), "--quiet"});
  ASSERT_EQ(stats.status, 0) << stats;
  EXPECT_TRUE(isPng(out / "stats" / "joint_angles.png"));
  const nlohmann::json filtering = nlohmann::json::parse(readFile(out / "stats" / "pose_filtering.json"));
  EXPECT_EQ(filtering["kept"], 3);
  EXPECT_EQ(filtering["simulated"].get<int>(),
            3 + manifest["stats"]["rejected_total"].get<int>());  // the tie's arms do not drive it: nothing pruned
  EXPECT_EQ(filtering["drawn"], filtering["simulated"]);
  // A necktie decoder learns from it; a whole-garment one does not fit the tie's images, and says so.
  const fs::path model = out / "model";
  const CliRun train = runPixelcloth({"train", "--dataset", data.string(), "--model", "necktie", "--width", "0.125",
                                      "--epochs", "2", "--batch", "2", "--out", model.string(), "--quiet"});
  ASSERT_EQ(train.status, 0) << train;
  EXPECT_EQ(train.err, "") << "--quiet silences progress";
  for (const char* name : {"model.tensors", "model.json", "log.csv", "training.png"})
    EXPECT_TRUE(fs::exists(model / name)) << name;
  EXPECT_EQ(nlohmann::json::parse(readFile(model / "model.json"))["architecture"], "necktie");
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", data.string(), "--model", "whole", "--epochs", "1", "--out",
                                     (out / "whole").string()}),
                      {"whole model does not fit", "necktie"}));
  EXPECT_FALSE(fs::exists(out / "whole" / "model.tensors"));
  // The same command again finds everything done and changes nothing.
  const std::string before = readFile(data / "positions.npy");
  const CliRun again = runPixelcloth({"generate", "--garment", "necktie", "--count", "3", "--seed", "5", "--body",
                                      body_.string(), "--out", data.string()});
  EXPECT_EQ(again.status, 0) << again;
  EXPECT_NE(again.err.find("0 samples simulated (3 already done"), std::string::npos) << again;
  EXPECT_EQ(readFile(data / "positions.npy"), before);
}

TEST_F(CliTest, GenerateRefusesBadSettings) {
  const fs::path out = dir("generate_bad");
  const CliRun zero = runPixelcloth({"generate", "--count", "0", "--out", (out / "a").string()});
  EXPECT_EQ(zero.status, 2) << zero;
  EXPECT_NE(zero.err.find("--count"), std::string::npos) << zero;
  const CliRun shard = runPixelcloth({"generate", "--count", "4", "--shard", "3/2", "--out", (out / "b").string()});
  EXPECT_EQ(shard.status, 2) << shard;
  EXPECT_NE(shard.err.find("3/2"), std::string::npos) << shard;
  const CliRun garment =
      runPixelcloth({"generate", "--count", "4", "--garment", "skirt", "--out", (out / "c").string()});
  EXPECT_EQ(garment.status, 2) << garment;
  EXPECT_NE(garment.err.find("skirt"), std::string::npos) << garment;
  const CliRun body =
      runPixelcloth({"generate", "--count", "4", "--body", (out / "nowhere").string(), "--out", (out / "d").string()});
  EXPECT_EQ(body.status, 2) << body;
  EXPECT_NE(body.err.find("nowhere"), std::string::npos) << body;
  const CliRun solver = runPixelcloth({"generate", "--count", "4", "--solver", "ipc", "--out", (out / "e").string()});
  EXPECT_TRUE(refused(solver, {"generate --solver", "'ipc'", "pd or newton"})) << solver;
  EXPECT_FALSE(fs::exists(out / "e"));
  EXPECT_TRUE(refused(runPixelcloth({"generate", "--count", "4", "--step-degrees", "0", "--out", (out / "f").string()}),
                      {"--step-degrees"}));
  EXPECT_FALSE(fs::exists(out / "f"));
  // Friction is the Newton solver's setting: with projective dynamics it is refused, naming both.
  const CliRun friction =
      runPixelcloth({"generate", "--count", "4", "--friction", "0.3", "--out", (out / "g").string()});
  EXPECT_TRUE(refused(friction, {"generate --friction", "--solver newton", "got --solver pd"})) << friction;
  EXPECT_FALSE(fs::exists(out / "g"));
}

TEST_F(CliDatasetTest, DatasetFilesAreVerifiedWhenOpenedUnlessNoVerify) {
  const fs::path data = work_ / "data";
  ASSERT_EQ(import(work_ / "objs", work_ / "poses.csv", data).status, 0);
  fs::copy(data, work_ / "damaged", fs::copy_options::recursive);
  std::string bytes = readFile(data / "positions.npy");
  bytes[bytes.size() - 8] ^= 0x01;  // a mantissa bit: the value stays finite (a NaN is refused even unverified)
  writeFile(work_ / "damaged" / "positions.npy", bytes);
  EXPECT_TRUE(refused(runPixelcloth({"images", "--dataset", (work_ / "damaged").string(), "--samples", "0", "--out",
                                     (work_ / "images").string()}),
                      {"positions.npy", "CRC-32", "--no-verify"}));
  EXPECT_TRUE(filesUnder(work_ / "images").empty());
  const CliRun run = runPixelcloth({"--no-verify", "images", "--dataset", (work_ / "damaged").string(), "--samples",
                                    "0", "--out", (work_ / "images").string(), "--quiet"});
  EXPECT_EQ(run.status, 0) << run;

  // A failed merge leaves neither its output folder nor a staging folder behind.
  EXPECT_TRUE(
      refused(runPixelcloth({"dataset", "merge", "--out", (work_ / "merged").string(), (work_ / "damaged").string()}),
              {"positions.npy", "CRC-32"}));
  EXPECT_FALSE(fs::exists(work_ / "merged"));
  for (const auto& entry : fs::directory_iterator(work_))
    EXPECT_EQ(entry.path().filename().string().find("merging"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace pixelcloth::apps
