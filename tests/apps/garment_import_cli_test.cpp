// `pixelcloth garment --import OBJ --cage JSON --out DIR`, run as a program: a garment folder the template form wrote
// comes back through the import form, and a broken cage is refused with exit code 2 before anything is written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "pixelcloth/core/json_io.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
using pixelcloth::testing::freshDir;

/// What one run of the binary did.
struct ImportRun {
  std::string command;
  int status = -1;  ///< exit code, or -1 when killed by a signal
  std::string out;
  std::string err;
};

std::ostream& operator<<(std::ostream& os, const ImportRun& run) {
  return os << "\n$ " << run.command << "\nexit code " << run.status << "\n--- stdout ---\n"
            << run.out.substr(0, 4000) << "\n--- stderr ---\n"
            << run.err.substr(0, 4000) << "\n";
}

std::string shellWord(const std::string& s) {
  std::string quoted = "'";
  for (char c : s) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `pixelcloth ARGS...` (each argument one shell word); stdout through a pipe, stderr through a file.
ImportRun runPixelcloth(std::initializer_list<std::string> args) {
  static int counter = 0;
  const fs::path errFile = fs::temp_directory_path() / ("pixelcloth-garment-import-cli-stderr." +
                                                        std::to_string(::getpid()) + "." + std::to_string(counter++));
  ImportRun run;
  run.command = shellWord(PIXELCLOTH_BINARY);
  for (const std::string& arg : args) run.command += " " + shellWord(arg);
  FILE* pipe = ::popen((run.command + " 2>" + shellWord(errFile.string())).c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) run.out.append(buffer, n);
  const int raw = ::pclose(pipe);
  run.status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.err = slurp(errFile);
  std::error_code ignored;
  fs::remove(errFile, ignored);
  return run;
}

/// Regular files under `dir` (none when it does not exist).
std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), dir).string());
  return files;
}

bool isPngFile(const fs::path& path) { return slurp(path).rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

/// Exit code 2, no internal error, and every one of `mentions` on stderr.
::testing::AssertionResult refusedWith(const ImportRun& run, const std::vector<std::string>& mentions) {
  if (run.status != 2) return ::testing::AssertionFailure() << "expected exit code 2" << run;
  if (run.err.find("internal error") != std::string::npos)
    return ::testing::AssertionFailure() << "bad input reported as an internal error" << run;
  for (const std::string& mention : mentions)
    if (run.err.find(mention) == std::string::npos)
      return ::testing::AssertionFailure() << "the message does not mention '" << mention << "'" << run;
  return ::testing::AssertionSuccess();
}

/// A necktie folder written by the template form, shared by the tests of this file.
class GarmentImportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = freshDir("work");
    const ImportRun run = runPixelcloth({"garment", "necktie", "--out", (work_ / "A").string()});
    ASSERT_EQ(run.status, 0) << run;
  }
  fs::path work_;
};

}  // namespace

TEST_F(GarmentImportCli, ImportsAnExportedNecktie) {
  const fs::path a = work_ / "A", b = work_ / "B";
  const ImportRun run = runPixelcloth({"garment", "--import", (a / "garment.obj").string(), "--cage",
                                       (a / "garment.json").string(), "--out", b.string()});
  ASSERT_EQ(run.status, 0) << run;
  const nlohmann::json exported = pixelcloth::core::readJson(a / "garment.json");
  const nlohmann::json imported = pixelcloth::core::readJson(b / "garment.json");
  EXPECT_EQ(imported.at("mesh").at("faces"), exported.at("mesh").at("faces"));
  EXPECT_EQ(imported.at("face_layout").size(), exported.at("face_layout").size());
  EXPECT_EQ(imported.at("cage_lines").size(), exported.at("cage_lines").size());
  EXPECT_EQ(imported.at("openings"), exported.at("openings"));
  EXPECT_TRUE(isPngFile(b / "pattern.png"));
  EXPECT_TRUE(isPngFile(b / "garment.png"));
  EXPECT_EQ(filesIn(b).size(), 4u);
}

TEST_F(GarmentImportCli, BrokenCageIsRefusedAndNothingIsWritten) {
  const fs::path a = work_ / "A", b2 = work_ / "B2";
  nlohmann::json cage = pixelcloth::core::readJson(a / "garment.json");
  ASSERT_FALSE(cage.at("cage_lines").empty());
  cage["cage_lines"][0]["kind"] = "zigzag";
  const fs::path broken = work_ / "broken.json";
  pixelcloth::core::writeJson(broken, cage);
  const ImportRun run = runPixelcloth(
      {"garment", "--import", (a / "garment.obj").string(), "--cage", broken.string(), "--out", b2.string()});
  EXPECT_TRUE(refusedWith(run, {broken.string(), "zigzag"}));
  EXPECT_TRUE(filesIn(b2).empty());
}

TEST_F(GarmentImportCli, ImportAndTemplateTogetherOrNeitherAreRefused) {
  const fs::path a = work_ / "A", out = work_ / "C";
  EXPECT_TRUE(refusedWith(runPixelcloth({"garment", "necktie", "--import", (a / "garment.obj").string(), "--cage",
                                         (a / "garment.json").string(), "--out", out.string()}),
                          {"necktie", "--import"}));
  EXPECT_TRUE(refusedWith(runPixelcloth({"garment", "--out", out.string()}), {"tshirt", "necktie", "--import"}));
  EXPECT_TRUE(refusedWith(runPixelcloth({"garment", "--import", (a / "garment.obj").string(), "--out", out.string()}),
                          {"--cage"}));
  EXPECT_TRUE(filesIn(out).empty());
}

TEST(GarmentImportCliHelp, ListsEveryOptionWithItsDefault) {
  const ImportRun run = runPixelcloth({"garment", "--help"});
  ASSERT_EQ(run.status, 0) << run;
  for (const std::string option : {"kind", "--import", "--cage", "--out", "--vertices", "tshirt", "necktie", "3000"})
    EXPECT_NE(run.out.find(option), std::string::npos) << option << run;
}
