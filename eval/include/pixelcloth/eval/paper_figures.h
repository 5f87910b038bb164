#pragma once

// The figures Jin et al. publish ("A Pixel-Based Framework for Data-Driven Clothing"), to print beside ours. Their
// data: PhysBAM quasistatic T-shirts on a scanned body, 20,011 samples (16K train, 2K regularisation, 2K test).
// Errors are mean per-vertex distances in cm; normal is the mean cosine distance 1 - n_pred . n_gt.

namespace pixelcloth::eval::paper {

struct Row {
  const char* label;
  double trainCm, trainNormal, testCm, testNormal;  ///< NaN-free: the paper gives all four where a row is listed
};

/// Table 1: the whole-garment CNN (90 -> 256 x 256 x 6) by its loss on grid pixels.
inline constexpr Row kTable1[] = {{"L1", 0.33, 0.020, 0.44, 0.027},
                                  {"L2", 0.35, 0.017, 0.47, 0.028},
                                  {"L2 + normal (0.01)", 0.37, 0.0075, 0.51, 0.029}};

/// Whole garment against 28 patch networks (its error-distribution figure): train and test vertex error.
struct TrainTest {
  const char* label;
  double trainCm, testCm;
};
inline constexpr TrainTest kWholeAgainstPatches[] = {{"whole T-shirt", 0.37, 0.51}, {"28 patch networks", 0.20, 0.46}};

/// Table 2: a fully connected network (2 x 256, ReLU), direct and through 128 principal components, by space.
struct FullyConnectedRow {
  const char* space;
  double directTrainCm, directTestCm, pcaTrainCm, pcaTestCm;
};
inline constexpr FullyConnectedRow kTable2[] = {
    {"local", 0.65, 0.67, 0.50, 0.55}, {"root", 0.69, 0.72, 0.53, 0.58}, {"positions", 0.63, 0.68, 0.58, 0.65}};

/// The PCA filter's best k in the paper (of 2048 kept).
inline constexpr int kBestPcaComponents = 2048;

}  // namespace pixelcloth::eval::paper
