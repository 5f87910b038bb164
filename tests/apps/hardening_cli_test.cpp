// Input that once crashed pixelcloth or reached an allocation it controlled: JSON nested thousands deep in files that
// get copied, counts and weights without an upper bound, an empty output name. Each is refused with exit code 2 and
// a message naming the file or option, before anything is written.
#include "cli_fixtures.h"

namespace pixelcloth::apps {
namespace {

/// 150,000 levels of brackets: about 300 KB, what overflowed the stack when nlohmann copied the value.
std::string depthBomb() { return std::string(150000, '[') + std::string(150000, ']'); }

/// `file`'s JSON with `key` set to the depth bomb, written back as text.
void plantBomb(const fs::path& file, const std::string& key) {
  std::string text = readFile(file);
  const size_t brace = text.rfind('}');
  ASSERT_NE(brace, std::string::npos) << file;
  text.insert(brace, ", \"" + key + "\": " + depthBomb());
  writeFile(file, text);
}

class HardeningCli : public CliTest {
 protected:
  void SetUp() override { work_ = dir("work"); }
  /// A two-sample necktie dataset and a tiny model trained on it.
  void makeDatasetAndModel() {
    CliRun run = runPixelcloth({"generate", "--garment", "necktie", "--count", "4", "--seed", "1", "--out",
                                (work_ / "tie").string(), "--quiet"});
    ASSERT_EQ(run.status, 0) << run;
    run = runPixelcloth({"train", "--dataset", (work_ / "tie").string(), "--model", "necktie", "--width", "0.0625",
                         "--epochs", "1", "--out", (work_ / "model").string(), "--quiet"});
    ASSERT_EQ(run.status, 0) << run;
  }
  fs::path work_;
};

TEST_F(HardeningCli, JsonNestedThousandsDeepIsRefusedNotACrash) {
  makeDatasetAndModel();
  if (HasFatalFailure()) return;
  // The dataset's manifest (no checksum guards it) with a deep "settings"-level key.
  const fs::path tie = work_ / "tie";
  const std::string manifest = readFile(tie / "manifest.json");
  plantBomb(tie / "manifest.json", "extra");
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "info", tie.string()}),
                      {(tie / "manifest.json").string(), "nested more than 64 levels"}));
  EXPECT_TRUE(refused(runPixelcloth({"dataset", "check", tie.string()}),
                      {(tie / "manifest.json").string(), "nested more than 64 levels"}));
  writeFile(tie / "manifest.json", manifest);
  // A model.json with a deep extra key.
  const fs::path model = work_ / "model" / "model.json";
  plantBomb(model, "notes");
  EXPECT_TRUE(refused(runPixelcloth({"predict", "--model", (work_ / "model").string(), "--dataset", tie.string(),
                                     "--samples", "0", "--out", (work_ / "out").string()}),
                      {"model.json", "nested more than 64 levels"}));
  EXPECT_FALSE(fs::exists(work_ / "out"));
}

TEST_F(HardeningCli, ANaNInADatasetIsRefusedAlsoWithoutChecksums) {
  const fs::path tie = work_ / "tie";
  const CliRun made = runPixelcloth(
      {"generate", "--garment", "necktie", "--count", "4", "--seed", "1", "--out", tie.string(), "--quiet"});
  ASSERT_EQ(made.status, 0) << made;
  core::NpyArray positions = core::readNpy(tie / "positions.npy");
  reinterpret_cast<float*>(positions.bytes.data())[positions.size() - 1] = std::numeric_limits<float>::infinity();
  core::writeNpy(tie / "positions.npy", positions);
  // --no-verify skips the checksums, not the values: training would log inf and NaN losses.
  EXPECT_TRUE(refused(runPixelcloth({"--no-verify", "train", "--dataset", tie.string(), "--model", "necktie", "--width",
                                     "0.0625", "--epochs", "1", "--out", (work_ / "model").string()}),
                      {(tie / "positions.npy").string(), "at row 4", "is not finite"}));
  EXPECT_FALSE(fs::exists(work_ / "model"));
}

TEST_F(HardeningCli, CountsAndWeightsHaveUpperBoundsAndMessagesStayShort) {
  const fs::path out = work_ / "huge";
  EXPECT_TRUE(refused(runPixelcloth({"generate", "--count", "2147483647", "--out", out.string()}),
                      {"--count 2147483647", "expected 1 to 10000000"}));
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", (work_ / "tie").string(), "--normal-weight", "-1", "--out",
                                     (work_ / "model").string()}),
                      {"--normal-weight"}));
  EXPECT_TRUE(refused(runPixelcloth({"train", "--dataset", (work_ / "tie").string(), "--edge-weight", "inf", "--out",
                                     (work_ / "model").string()}),
                      {"--edge-weight"}));
  EXPECT_TRUE(refused(runPixelcloth({"pose", "--random", "0", "--out", (work_ / "poses").string()}),
                      {"--random", "not in range 1 to 10000"}));
  for (const char* option : {"--side", "--amplitude"}) {
    const CliRun run = runPixelcloth({"bases", "--figures", (work_ / "figures").string(), option, "0"});
    EXPECT_TRUE(refused(run, {option}));
    EXPECT_LT(run.err.size(), 300u) << "a range of 309-digit numbers?" << run;
  }
  EXPECT_FALSE(fs::exists(work_ / "figures"));
}

TEST_F(HardeningCli, AnEmptyOutputNameIsRefused) {
  EXPECT_TRUE(refused(runPixelcloth({"generate", "--count", "1", "--garment", "necktie", "--out", ""}),
                      {"empty output folder name"}));
  EXPECT_TRUE(refused(runPixelcloth({"view", work_.string(), "--out", ""}), {"--out", "empty folder name"}));
  EXPECT_TRUE(filesUnder(work_).empty());
}

}  // namespace
}  // namespace pixelcloth::apps
