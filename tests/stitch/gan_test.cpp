// The GAN blender: both networks have pix2pix's shapes and sizes, a step trains them, cloth images go through tensors
// unchanged, and trainGan on a tiny patch model writes a blender that reloads to its recorded error; damaged, missing
// and foreign files are refused.
#include "pixelcloth/stitch/gan.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gan_networks.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/learn/train.h"
#include "pixelcloth/stitch/evaluate.h"
#include "support/body_fixtures.h"
#include "support/fixtures.h"
#include "support/synthetic_dataset.h"
#include "support/test_util.h"

namespace {

namespace fs = std::filesystem;
namespace pb = pixelcloth::body;
namespace pc = pixelcloth::core;
namespace pd = pixelcloth::data;
namespace pg = pixelcloth::garment;
namespace pl = pixelcloth::learn;
namespace ps = pixelcloth::stitch;
using pixelcloth::testing::inputErrorOf;

/// pix2pix's unet_256 at width 1 has 54,413,955 parameters for 3 -> 3 channels (its paper's code prints 54.414 M);
/// ours takes and gives 6: 3 x 64 x 16 more weights in the first layer, 3 x 128 x 16 + 3 in the last.
constexpr std::int64_t kGeneratorParametersAtWidth1 = 54413955 + 3 * 64 * 16 + 3 * 128 * 16 + 3;
/// Its 70 x 70 PatchGAN (n_layers 3) on 6 channels: 2,768,705 (2.769 M); ours sees 12: 6 x 64 x 16 more.
constexpr std::int64_t kDiscriminatorParametersAtWidth1 = 2768705 + 6 * 64 * 16;

/// The generator's parameters counted from its channels (c: the eight encoder levels'), as the layers are listed in
/// gan_networks.h: no bias where BatchNorm follows, BatchNorm (2 per channel) on all but the first and innermost
/// encoder convolutions and the last decoder one.
std::int64_t generatorParameters(const std::int64_t c[8]) {
  std::int64_t n = 6 * c[0] * 16;
  for (int i = 1; i < 8; ++i) n += c[i - 1] * c[i] * 16 + (i < 7 ? 2 * c[i] : 0);
  n += c[7] * c[6] * 16 + 2 * c[6];
  for (int i = 6; i >= 1; --i) n += 2 * c[i] * c[i - 1] * 16 + 2 * c[i - 1];
  return n + 2 * c[0] * 6 * 16 + 6;
}

TEST(Gan, SummaryHasPix2pixShapesAndSizesAtTwoWidths) {
  const nlohmann::json one = ps::ganSummary(1.0), eighth = ps::ganSummary(0.125);
  for (const nlohmann::json& s : {one, eighth}) {
    EXPECT_EQ(s["generator"]["output"], (std::vector<std::int64_t>{6, 256, 256}));
    EXPECT_EQ(s["discriminator"]["output"], (std::vector<std::int64_t>{1, 30, 30}));  // 70 x 70 windows, stride 8
    ASSERT_EQ(s["generator"]["layers"].size(), 16u);
    EXPECT_EQ(s["generator"]["layers"][7]["output"].back(), 1);  // the innermost code is 1 x 1
  }
  EXPECT_EQ(one["generator"]["parameters"], kGeneratorParametersAtWidth1);
  EXPECT_EQ(one["discriminator"]["parameters"], kDiscriminatorParametersAtWidth1);
  EXPECT_EQ(one["generator"]["layers"][0]["output"], (std::vector<std::int64_t>{64, 128, 128}));
  const std::int64_t c[8] = {8, 16, 32, 64, 64, 64, 64, 64};
  EXPECT_EQ(eighth["generator"]["parameters"], generatorParameters(c));
  EXPECT_EQ(eighth["generator"]["layers"][0]["output"], (std::vector<std::int64_t>{8, 128, 128}));
  EXPECT_EQ(eighth["discriminator"]["parameters"],
            12 * 8 * 16 + 8 + 8 * 16 * 16 + 32 + 16 * 32 * 16 + 64 + 32 * 64 * 16 + 128 + 64 * 16 + 1);
  const std::int64_t full[8] = {64, 128, 256, 512, 512, 512, 512, 512};
  EXPECT_EQ(generatorParameters(full), kGeneratorParametersAtWidth1);  // the formula above is pix2pix's count
}

/// Two smooth images of the T-shirt and targets a centimetre-sized bulge away.
struct Images {
  torch::Tensor x, y;
};
Images smoothImages(const ps::ClothTensors& images) {
  const Eigen::MatrixXf a = pixelcloth::testing::smoothOffsets(pixelcloth::testing::tshirt());
  const Eigen::MatrixXf b = 0.5 * a, c = a + Eigen::MatrixXf::Constant(a.rows(), 3, 0.01f),
                        d = b.array().sin().matrix();
  return {images.images({&a, &b}), images.images({&c, &d})};
}

std::vector<torch::Tensor> copies(const torch::nn::Module& module) {
  std::vector<torch::Tensor> out;
  for (const torch::Tensor& p : module.parameters()) out.push_back(p.detach().clone());
  return out;
}

bool same(const std::vector<torch::Tensor>& a, const std::vector<torch::Tensor>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (!torch::equal(a[k], b[k])) return false;
  return true;
}

TEST(Gan, AnUntrainedGeneratorIsTheIdentityAndOneStepTrainsBothNetworks) {
  const ps::ClothTensors images(pixelcloth::testing::tshirt(), "test");
  const Images data = smoothImages(images);
  ps::GanNetworks networks(0.0625, 2e-4, 7);
  {
    torch::NoGradGuard noGrad;
    networks.generator->eval();
    EXPECT_TRUE(torch::equal(networks.generator->forward(data.x), data.x));
  }
  const std::vector<torch::Tensor> generator = copies(*networks.generator),
                                   discriminator = copies(*networks.discriminator);
  const ps::GanStepLosses losses = networks.step(data.x, data.y, images.mask(), 100);
  EXPECT_TRUE(std::isfinite(losses.l1) && std::isfinite(losses.adversarial) && std::isfinite(losses.discriminator));
  EXPECT_GT(losses.l1, 0.001);                            // the targets are centimetres away on the mask
  EXPECT_NEAR(losses.discriminator, std::log(2.0), 0.1);  // an untrained discriminator guesses
  EXPECT_FALSE(same(copies(*networks.generator), generator));
  EXPECT_FALSE(same(copies(*networks.discriminator), discriminator));
  // The same seed gives the same networks, another seed others.
  ps::GanNetworks again(0.0625, 2e-4, 7), other(0.0625, 2e-4, 8);
  EXPECT_TRUE(same(copies(*again.generator), generator));
  EXPECT_TRUE(same(copies(*again.discriminator), discriminator));
  EXPECT_FALSE(same(copies(*other.generator), generator));
  // The L1 counts on the mask only: targets changed outside it give the same loss.
  const torch::Tensor outside = data.y + (1 - images.mask()) * 5.0;
  EXPECT_DOUBLE_EQ(again.step(data.x, outside, images.mask(), 100).l1, losses.l1);
  // More steps move the generator's output towards the targets (its L1, measured in each step, falls).
  double l1 = losses.l1;
  for (int k = 0; k < 10; ++k) l1 = networks.step(data.x, data.y, images.mask(), 100).l1;
  std::cout << "[width 0.0625] L1 " << losses.l1 << " m at the first step, " << l1 << " m at the 11th\n";
  EXPECT_LT(l1, 0.9 * losses.l1);
}

TEST(Gan, ClothImagesGoThroughTensorsInChannelOrder) {
  const pg::Garment& shirt = pixelcloth::testing::tshirt();
  const ps::ClothTensors images(shirt, "test");
  const Eigen::MatrixXf x = pixelcloth::testing::smoothOffsets(shirt);
  const torch::Tensor t = images.images({&x});
  ASSERT_EQ(t.sizes(), (std::vector<std::int64_t>{1, 6, 256, 256}));
  const pixelcloth::patches::ClothImage image = images.imager().rasterize(x);
  const Eigen::MatrixXf* expected[6] = {&image.layer("front").du, &image.layer("front").dv, &image.layer("front").dn,
                                        &image.layer("back").du,  &image.layer("back").dv,  &image.layer("back").dn};
  for (int c = 0; c < 6; ++c)
    for (int row : {0, 77, 128, 200})
      for (int column : {3, 100, 128, 250})
        EXPECT_EQ(t[0][c][row][column].item<float>(), (*expected[c])(row, column)) << c << " " << row << " " << column;
  // Rasterise, to a tensor, back: the imager's own round trip (within a bound of the input).
  const Eigen::MatrixXf back = images.values(t[0]);
  EXPECT_EQ(back, images.imager().sample(image));
  EXPECT_LT((back - x).cwiseAbs().maxCoeff(), 2e-3);
  EXPECT_GT(images.mask().sum().item<double>(), 0.2 * 6 * 256 * 256);
  EXPECT_EQ(images.mask()[0].sum().item<double>(), images.mask()[2].sum().item<double>());
  const pg::Garment tie = pg::makeGarment("necktie", "test");
  EXPECT_NE(inputErrorOf([&] { ps::ClothTensors(tie, "tie"); }).find("6 x 256 x 256"), std::string::npos);
}

TEST(Gan, OptionsOutOfRangeAreRefused) {
  EXPECT_NO_THROW(ps::GanOptions().validate());
  auto refused = [](auto change, const std::string& field) {
    ps::GanOptions options;
    change(options);
    const std::string message = inputErrorOf([&] { options.validate(); });
    EXPECT_NE(message.find(field), std::string::npos) << message;
  };
  refused([](ps::GanOptions& o) { o.width = 0; }, "width");
  refused([](ps::GanOptions& o) { o.width = 4.5; }, "width");
  refused([](ps::GanOptions& o) { o.width = std::nan(""); }, "width");
  refused([](ps::GanOptions& o) { o.epochs = 0; }, "epochs");
  refused([](ps::GanOptions& o) { o.batch = 0; }, "batch");
  refused([](ps::GanOptions& o) { o.learningRate = -1; }, "learning rate");
  refused([](ps::GanOptions& o) { o.l1Weight = -1; }, "L1 weight");
  refused([](ps::GanOptions& o) { o.threads = -2; }, "threads");
}

/// The dataset, its 28 tiny patch decoders (one epoch) and a blender trained on them (two epochs), made once.
struct Trained {
  fs::path dataset, patches, blender;
  pl::TrainingData data;
  std::unique_ptr<pl::TrainedModel> patchModel;
  ps::GanReport report;
  ps::GanOptions options;
};

const Trained& trained() {
  static const Trained t = [] {
    Trained t;
    t.dataset = pixelcloth::testing::syntheticDataset("gan", "tshirt", 6);  // 5 train, 1 regularisation
    const fs::path root = t.dataset.parent_path() / ("gan-models." + std::to_string(::getpid()));
    fs::remove_all(root);
    t.patches = root / "patches";
    t.blender = root / "blender";
    pl::TrainOptions patch;
    patch.model.architecture = pl::Architecture::Patch;
    patch.model.width = 0.0625;
    patch.epochs = 1;
    patch.batch = 2;
    pl::train(t.dataset, t.patches, patch);
    t.data = pl::loadTrainingData(t.dataset, pl::OffsetSpace::Local, {});
    t.patchModel = std::make_unique<pl::TrainedModel>(t.patches, t.data.garment);
    t.options.width = 0.0625;
    t.options.epochs = 2;
    t.options.batch = 2;
    t.options.seed = 3;
    t.report = ps::trainGan(*t.patchModel, t.data, t.options, t.blender);
    return t;
  }();
  return t;
}

TEST(Gan, TrainsOnAPatchModelAndReloadsToItsRecordedError) {
  const Trained& t = trained();
  ASSERT_EQ(t.report.epochs.size(), 2u);
  ASSERT_GE(t.report.bestEpoch, 1);
  for (const ps::GanEpoch& e : t.report.epochs) {
    EXPECT_TRUE(std::isfinite(e.generatorL1) && std::isfinite(e.generatorAdversarial) &&
                std::isfinite(e.discriminator));
    EXPECT_TRUE(std::isfinite(e.regularisationErrorCm));
    EXPECT_EQ(e.stitchedErrorCm, t.report.epochs.front().stitchedErrorCm);
    EXPECT_GT(e.stitchedErrorCm, 0);
  }
  const std::string log = pc::readTextFile(t.blender / "log.csv");
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 3);
  const nlohmann::json info = pc::readJson(t.blender / "model.json");
  EXPECT_EQ(info["architecture"], "gan");
  EXPECT_EQ(info["format"], "pixelcloth.model");
  EXPECT_EQ(info["width"], 0.0625);
  EXPECT_EQ(info["epoch"], t.report.bestEpoch);
  EXPECT_EQ(info["garment"], "tshirt");
  EXPECT_EQ(info["space"], "local");
  EXPECT_EQ(info["dataset_manifest_crc32"], t.data.manifestCrc);
  EXPECT_EQ(fs::path(info["patch_model"].get<std::string>()), fs::absolute(t.patches).lexically_normal());
  for (const auto& entry : fs::directory_iterator(t.blender))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();  // written atomically

  // Reloaded, the blender gives the regularisation error model.json and the report recorded for its epoch.
  const ps::GanBlender blender(t.blender, t.data.garment);
  EXPECT_EQ(blender.info()["epoch"], t.report.bestEpoch);
  const std::vector<int>& rows = t.data.regularisation;
  ASSERT_EQ(rows.size(), 1u);
  const ps::RowPredictions stitched = ps::predictRows(*t.patchModel, t.data, rows);
  const int V = t.data.garment.mesh.numVertices();
  Eigen::MatrixXf batch(1, 3 * V);
  for (int v = 0; v < V; ++v) batch.block<1, 3>(0, 3 * v) = stitched.values[0].row(v);
  const Eigen::MatrixXf blended = blender.blend(batch);
  ASSERT_EQ(blended.rows(), 1);
  ASSERT_EQ(blended.cols(), 3 * V);
  EXPECT_TRUE(blended.allFinite());
  Eigen::MatrixX3f values(V, 3);
  for (int v = 0; v < V; ++v) values.row(v) = blended.block<1, 3>(0, 3 * v);
  const Eigen::MatrixX3d positions = pl::positionsFromValues(t.data.space, t.data.frames[rows[0]], values);
  const double error = 100 * (positions - t.data.truth[rows[0]].cast<double>()).rowwise().norm().mean();
  EXPECT_NEAR(error, t.report.epochs[t.report.bestEpoch - 1].regularisationErrorCm, 1e-4);
  EXPECT_NEAR(error, info["regularisation_error_cm"].get<double>(), 1e-4);
  // The stitched input's error, as predictRows' positions give it.
  const double stitchedError =
      100 * (stitched.positions[0] - t.data.truth[rows[0]].cast<double>()).rowwise().norm().mean();
  EXPECT_NEAR(stitchedError, t.report.epochs.front().stitchedErrorCm, 1e-6);
  EXPECT_NE(inputErrorOf([&] { blender.blend(batch.leftCols(9)); }).find("expected batch x"), std::string::npos);
}

TEST(Gan, TheSameSeedTrainsTheSameBlender) {
  const Trained& t = trained();
  const fs::path again = pixelcloth::testing::freshDir("again");
  const ps::GanReport report = ps::trainGan(*t.patchModel, t.data, t.options, again);
  ASSERT_EQ(report.epochs.size(), t.report.epochs.size());
  for (size_t k = 0; k < report.epochs.size(); ++k) {
    EXPECT_EQ(report.epochs[k].generatorL1, t.report.epochs[k].generatorL1);
    EXPECT_EQ(report.epochs[k].regularisationErrorCm, t.report.epochs[k].regularisationErrorCm);
  }
  EXPECT_EQ(pc::readTextFile(again / "model.tensors"), pc::readTextFile(t.blender / "model.tensors"));
}

TEST(Gan, DamagedMissingAndForeignFilesAreRefused) {
  const Trained& t = trained();
  const fs::path copy = pixelcloth::testing::freshDir("copy");
  for (const char* name : {"model.json", "model.tensors"}) fs::copy_file(t.blender / name, copy / name);
  EXPECT_NO_THROW(ps::GanBlender(copy, t.data.garment));
  const std::string weights = pc::readTextFile(copy / "model.tensors");
  pc::writeTextAtomically(copy / "model.tensors", weights.substr(0, weights.size() / 2));
  const std::string truncated = inputErrorOf([&] { ps::GanBlender(copy, t.data.garment); });
  EXPECT_NE(truncated.find("model.tensors"), std::string::npos) << truncated;
  // A patch decoder's weights are not a generator's.
  fs::copy_file(t.patches / "patch_00" / "model.tensors", copy / "model.tensors", fs::copy_options::overwrite_existing);
  const std::string foreign = inputErrorOf([&] { ps::GanBlender(copy, t.data.garment); });
  EXPECT_NE(foreign.find("model.tensors"), std::string::npos) << foreign;
  pc::writeTextAtomically(copy / "model.tensors", weights);
  // Another width in model.json than the weights have.
  nlohmann::json info = pc::readJson(copy / "model.json");
  info["width"] = 0.125;
  pc::writeJson(copy / "model.json", info);
  const std::string wider = inputErrorOf([&] { ps::GanBlender(copy, t.data.garment); });
  EXPECT_NE(wider.find("model.tensors"), std::string::npos) << wider;
  // A patch decoder's model.json, and another garment.
  fs::copy_file(t.patches / "patch_00" / "model.json", copy / "model.json", fs::copy_options::overwrite_existing);
  const std::string patch = inputErrorOf([&] { ps::GanBlender(copy, t.data.garment); });
  EXPECT_NE(patch.find("expected a GAN blender"), std::string::npos) << patch;
  fs::copy_file(t.blender / "model.json", copy / "model.json", fs::copy_options::overwrite_existing);
  const std::string tie = inputErrorOf([&] { ps::GanBlender(copy, pg::makeGarment("necktie", "test")); });
  EXPECT_NE(tie.find("not of this necktie"), std::string::npos) << tie;
  EXPECT_NE(tie.find("model.json"), std::string::npos) << tie;
  fs::remove(copy / "model.json");
  const std::string missing = inputErrorOf([&] { ps::GanBlender(copy, t.data.garment); });
  EXPECT_NE(missing.find("model.json"), std::string::npos) << missing;
}

TEST(Gan, RefusesAModelThatIsNotAPatchModelOrWasTrainedOnOtherData) {
  const Trained& t = trained();
  const fs::path whole = pixelcloth::testing::freshDir("whole"), out = pixelcloth::testing::freshDir("out");
  pl::TrainOptions options;
  options.model.architecture = pl::Architecture::Whole;
  options.model.width = 0.03125;
  options.epochs = 1;
  pl::train(t.dataset, whole, options);
  const pl::TrainedModel wholeModel(whole, t.data.garment);
  const std::string notPatch = inputErrorOf([&] { ps::trainGan(wholeModel, t.data, t.options, out / "a"); });
  EXPECT_NE(notPatch.find("whole model"), std::string::npos) << notPatch;
  EXPECT_NE(notPatch.find(whole.string()), std::string::npos) << notPatch;
  pl::TrainingData other = t.data;
  other.manifestCrc ^= 1;
  const std::string foreign = inputErrorOf([&] { ps::trainGan(*t.patchModel, other, t.options, out / "b"); });
  EXPECT_NE(foreign.find("manifest CRC"), std::string::npos) << foreign;
  EXPECT_NE(foreign.find(t.patches.string()), std::string::npos) << foreign;
  EXPECT_FALSE(fs::exists(out / "a"));
  EXPECT_FALSE(fs::exists(out / "b"));
}

}  // namespace
