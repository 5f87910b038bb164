#pragma once

// The demo's sections: each runs one stage on the built-in body and garments through the library, draws its pictures
// and adds its figures and a section to the report. `pixelcloth demo` calls them in order.

#include <cstdint>

#include "pixelcloth/body/body.h"
#include "pixelcloth/viz/report.h"

namespace pixelcloth::viz {

/// How much the demo does.
struct DemoOptions {
  int poses = 12;          ///< random poses shown
  int filterPoses = 200;   ///< poses drawn, pruned and simulated for the filtering histograms
  int tshirtSamples = 40;  ///< the simulated T-shirt dataset; its test split is rebuilt from markers
  int learningEpochs = 8;  ///< epochs of each learned model on that dataset
  int ownGarmentSamples = 20;  ///< the simulated dataset of the imported garment (demoOwnGarment)
  std::uint64_t seed = 1;
};

/// The built-in mannequin, its folder (body/) and its sheet: shaded with skeleton, skin weights, parts.
body::Body demoBody(Report& report);

/// The cage on the body (body/cage.json, body/cage.png).
void demoBodyCage(Report& report, const body::Body& body);

/// The mannequin at shape -1, 0 and 2 (shapes.png).
void demoShapes(Report& report, const body::Body& body);

/// One pose with the bone-heat weights and with corrupted upper-arm weights (skinning_artifacts.png).
void demoSkinningArtifacts(Report& report, const body::Body& body);

/// `demo.poses` poses from the appendix sampler, skinned (poses/).
void demoPoses(Report& report, const body::Body& body, const DemoOptions& demo);

/// An A-posed copy of the body written as OBJ + joints JSON and imported back (import/).
void demoBodyImport(Report& report, const body::Body& body);

/// The T-shirt and necktie patterns, folders and rest placements (tshirt/, necktie/).
void demoGarments(Report& report, const body::Body& body);

/// Each garment's cage and patches (tshirt/cage.png, necktie/cage.png).
void demoCageAndPatches(Report& report);

/// The appendix's basis figures (bases/).
void demoBases(Report& report);

/// A cage-driven fill of the T-shirt rasterised to cloth images, then edited (images/).
void demoClothImages(Report& report);

/// Both garments dressed on the body (dressing/).
void demoDressing(Report& report, const body::Body& body);

/// A simulated T-shirt dataset of `demo.tshirtSamples` samples, checked, with a contact sheet (dataset_tshirt/).
void demoTShirtDataset(Report& report, const body::Body& body, const DemoOptions& demo);

/// The T-shirt dataset's test split rebuilt from markers by every method (reconstruction/); needs demoTShirtDataset.
void demoReconstruction(Report& report, const body::Body& body);

/// A T-shirt OBJ written as other cloth programs write theirs (tube sleeves, Z up, centimetres, another origin),
/// imported without a cage file, fitted to the body (cage lines and patches), and taken through dressing,
/// `demo.ownGarmentSamples` simulated samples, marker reconstruction, per-patch decoders, prediction and evaluation
/// (own_garment/); needs demoBody's folder.
void demoOwnGarment(Report& report, const body::Body& body, const DemoOptions& demo);

/// A simulated necktie dataset of 6 samples, checked, with a contact sheet (dataset_necktie/).
void demoNecktieDataset(Report& report, const body::Body& body, const DemoOptions& demo);

/// `demo.filterPoses` sampler draws simulated on the T-shirt; joint-angle histograms before and after filtering.
void demoPoseSampling(Report& report, const body::Body& body, const DemoOptions& demo);

/// The paper's decoders and the fully connected baselines at full and quarter width: parameters, shapes and forward
/// cost, and one forward pass of each quarter-width decoder timed on this machine.
void demoNetworks(Report& report);

/// The learned models on the T-shirt dataset (needs demoTShirtDataset): a whole-garment decoder, the 28 patch
/// decoders and the residual patch decoders on the marker reconstruction of each sample, trained briefly and
/// compared on the test split with the marker reconstruction alone.
void demoLearning(Report& report, const body::Body& body, const DemoOptions& demo);

/// The patch decoders of demoLearning stitched every way (mean, feather, the PCA filter at the k the regularisation
/// split chooses, a GAN blender trained here) and measured on the test split, with the paper's tables (losses, whole
/// against patches, the baselines in three spaces) trained here: seams/report.md and its pictures.
void demoSeams(Report& report, const body::Body& body, const DemoOptions& demo);

}  // namespace pixelcloth::viz
