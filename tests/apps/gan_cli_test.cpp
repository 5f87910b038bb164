// train --model gan as a program: what it needs is checked before anything is read or written.
#include <gtest/gtest.h>

#include "support/cli.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
using pixelcloth::testing::filesUnder;
using pixelcloth::testing::refused;
using pixelcloth::testing::runPixelcloth;

TEST(GanCli, TheBlenderNeedsAPatchModelAndOnlyItsOwnOptions) {
  const fs::path work = pixelcloth::testing::freshDir("work"), out = work / "blender";
  // The checks come before the dataset is read: a folder that is no dataset does not mask them.
  const std::string dataset = work.string();
  EXPECT_TRUE(refused(runPixelcloth({"train", "--model", "gan", "--dataset", dataset, "--out", out.string()}),
                      {"--patch-model", "train --model gan"}));
  EXPECT_TRUE(refused(runPixelcloth({"train", "--model", "gan", "--patch-model", (work / "p").string(), "--dataset",
                                     dataset, "--space", "root", "--out", out.string()}),
                      {"--space", "not an option of the blender"}));
  EXPECT_TRUE(refused(runPixelcloth({"train", "--model", "gan", "--patch-model", (work / "p").string(), "--dataset",
                                     dataset, "--width", "0", "--out", out.string()}),
                      {"width 0"}));
  EXPECT_TRUE(refused(runPixelcloth({"train", "--model", "whole", "--patch-model", (work / "p").string(), "--dataset",
                                     dataset, "--out", out.string()}),
                      {"--patch-model", "--model gan"}));
  EXPECT_TRUE(refused(
      runPixelcloth({"train", "--model", "patch", "--l1-weight", "10", "--dataset", dataset, "--out", out.string()}),
      {"--l1-weight"}));
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(filesUnder(work).empty());
  const pixelcloth::testing::CliRun help = runPixelcloth({"train", "--help"});
  EXPECT_EQ(help.status, 0);
  for (const char* option : {"gan", "--patch-model", "--l1-weight"})
    EXPECT_NE(help.out.find(option), std::string::npos) << option;
}

}  // namespace
