// The one rule for writing into a used folder: another kind of run, or the same kind with other settings, is refused
// naming what is there; an empty folder, a missing one, or the same settings pass.
#include "pixelcloth/core/run_folder.h"

#include <gtest/gtest.h>

#include "pixelcloth/core/json_io.h"
#include "support/test_util.h"

namespace pixelcloth::core {
namespace {

using testing::freshDir;
using testing::inputErrorOf;

TEST(RunFolder, AnotherKindOrOtherSettingsAreRefusedTheSameSettingsPass) {
  const auto dir = freshDir("run_folder");
  const RunDescription filter{"pca.json", {{"components", 8}, {"space", "local"}}, "a PCA filter"};
  EXPECT_NO_THROW(checkRunFolder(dir / "missing", filter));
  EXPECT_NO_THROW(checkRunFolder(dir, filter));  // empty
  writeJson(dir / "notes.json", {{"anything", 1}});
  EXPECT_NO_THROW(checkRunFolder(dir, filter));  // not one of ours

  writeJson(dir / "pca.json", {{"format", "pixelcloth.pca"}, {"components", 8}, {"space", "local"}});
  EXPECT_NO_THROW(checkRunFolder(dir, filter));  // the same run again
  const RunDescription wider{"pca.json", {{"components", 16}, {"space", "local"}}, "a PCA filter"};
  const std::string other = inputErrorOf([&] { checkRunFolder(dir, wider); });
  EXPECT_NE(other.find("pca.json: the folder holds a run with components 8, this one's is 16"), std::string::npos)
      << other;
  const RunDescription unset{"pca.json", {{"rank", 4}}, "a PCA filter"};
  EXPECT_NE(inputErrorOf([&] { checkRunFolder(dir, unset); }).find("rank unset"), std::string::npos);

  writeJson(dir / "manifest.json", {{"format", "pixelcloth.dataset"}});
  const std::string dataset = inputErrorOf([&] { checkRunFolder(dir, filter); });
  EXPECT_NE(dataset.find("holds a dataset (manifest.json); a PCA filter goes in a folder of its own"),
            std::string::npos)
      << dataset;
  // A run without a descriptor of its own at the top (a patch model) is refused by any.
  EXPECT_NE(inputErrorOf([&] {
              checkRunFolder(dir, {"", {}, "a patch model"});
            }).find("holds a dataset"),
            std::string::npos);
}

// manifest.json describes a dataset or a base folder: the message says which by its format, and a base folder is not
// written over a dataset.
TEST(RunFolder, AManifestIsNamedByItsFormat) {
  const auto dir = freshDir("run_folder_manifest");
  const RunDescription base{"manifest.json", {{"format", "pixelcloth.base"}}, "a base folder"};
  writeJson(dir / "manifest.json", {{"format", "pixelcloth.base"}, {"version", 1}});
  EXPECT_NO_THROW(checkRunFolder(dir, base));
  EXPECT_NE(inputErrorOf([&] {
              checkRunFolder(dir, {"model.json", {}, "a model"});
            }).find("holds a base folder (manifest.json)"),
            std::string::npos);
  writeJson(dir / "manifest.json", {{"format", "pixelcloth.dataset"}, {"version", 1}});
  const std::string over = inputErrorOf([&] { checkRunFolder(dir, base); });
  EXPECT_NE(over.find("holds a dataset (manifest.json); a base folder goes in a folder of its own"), std::string::npos)
      << over;
  writeJson(dir / "manifest.json", {{"format", 3}});  // unreadable format: the general name
  EXPECT_NE(inputErrorOf([&] {
              checkRunFolder(dir, {"model.json", {}, "a model"});
            }).find("holds a dataset or base folder"),
            std::string::npos);
}

TEST(RunFolder, APatchModelIsRecognisedByItsDecoders) {
  const auto dir = freshDir("run_folder_patch");
  writeJson(dir / "patch_03" / "model.json", {{"format", "pixelcloth.model"}, {"width", 0.125}});
  EXPECT_NE(inputErrorOf([&] {
              checkRunFolder(dir, {"model.json", {}, "the fc model"});
            }).find("holds a patch model (patch_03/model.json); the fc model goes in a folder of its own"),
            std::string::npos);
  EXPECT_NO_THROW(checkRunFolder(dir, {kPatchModelFile, {}, "the patch model"}));
  // Each decoder folder is checked as a run of its own.
  EXPECT_NE(inputErrorOf([&] {
              checkRunFolder(dir / "patch_03", {"model.json", {{"width", 0.25}}, "a decoder"});
            }).find("width 0.125, this one's is 0.25"),
            std::string::npos);
}

}  // namespace
}  // namespace pixelcloth::core
