#pragma once

// The demo's sections: each draws one stage on the built-in body and garments, adds its figures and a section to the
// report. The cheap stages (the body, garments, cage, bases, dressing) run here; what simulates, trains or chooses a
// model runs in eval/demo.h and comes here as its typed result. `pixelcloth demo` calls them in order.

#include <cstdint>

#include "pixelcloth/body/body.h"
#include "pixelcloth/eval/demo.h"
#include "pixelcloth/viz/report.h"
#include "pixelcloth/viz/viewer.h"

namespace pixelcloth::viz {

/// The built-in mannequin, its folder (body/) and its sheet: shaded with skeleton, skin weights, parts.
body::Body demoBody(Report& report);

/// The cage on the body (body/cage.json, body/cage.png).
void demoBodyCage(Report& report, const body::Body& body);

/// The mannequin at shape -1, 0 and 2 (shapes.png).
void demoShapes(Report& report, const body::Body& body);

/// One pose with the bone-heat weights and with corrupted upper-arm weights (skinning_artifacts.png).
void demoSkinningArtifacts(Report& report, const body::Body& body);

/// `count` poses from the appendix sampler, skinned (poses/).
void demoPoses(Report& report, const body::Body& body, int count, std::uint64_t seed);

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

/// The dressed garments' folders and pictures (dressing/).
void demoDressing(Report& report, const body::Body& body, const std::vector<eval::DressedGarment>& dressed);

/// The simulated T-shirt dataset: a contact sheet (dataset_tshirt/contact_sheet.png) and its figures.
void demoTShirtDataset(Report& report, const body::Body& body, const eval::SimulatedDataset& made);

/// The T-shirt dataset's test split rebuilt from markers by every method: error maps and the rebuilt shirts beside
/// ground truth (reconstruction/).
void demoReconstruction(Report& report, const body::Body& body, const eval::DemoReconstruction& made);

/// A garment brought as another program's OBJ, through the pipeline: its pattern with the fitted cage lines, its
/// dressing, a prediction beside ground truth (own_garment/).
void demoOwnGarment(Report& report, const body::Body& body, const eval::OwnGarment& own);

/// The T-shirt's first poses at static equilibrium (Newton) beside projective dynamics' samples of them: the solver's
/// figures and the three poses where the two differ most, coloured by the distance (dataset_tshirt_newton/).
void demoEquilibrium(Report& report, const body::Body& body, const eval::EquilibriumDemo& made);

/// The simulated necktie dataset: a contact sheet (dataset_necktie/contact_sheet.png) and its figures.
void demoNecktieDataset(Report& report, const body::Body& body, const eval::SimulatedDataset& made);

/// Joint-angle histograms of the sampler's draws before and after pruning and simulation (poses/).
void demoPoseSampling(Report& report, const eval::PoseFiltering& filtering);

/// The paper's decoders and the fully connected baselines at full and quarter width: parameters, shapes and forward
/// cost, one forward pass of each quarter-width decoder timed on this machine, and the training curves of `necktie`
/// (model_necktie/training.png).
void demoNetworks(Report& report, const learn::TrainReport& necktie);

/// The learned models on the T-shirt dataset beside ground truth and the marker reconstruction alone
/// (learning/predictions.png, learning/error_maps.png, each model's training.png).
void demoLearning(Report& report, const body::Body& body, const eval::DemoLearning& learning);

/// The seam report of the stitched patch decoders with the paper's tables on the demo's shirts (seams/report.md and
/// its pictures).
void demoSeams(Report& report, const body::Body& body, const eval::DemoSeams& seams);

/// The demo's own motion through the patch decoders (motion/): the clip's strip, the garment on the moving body, the
/// temporal measures.
void demoMotion(Report& report, const body::Body& body, const eval::DemoMotion& demo);
/// The 3D viewer of the report (view/, written by the demo's last step): a section linking it with its scenes by group,
/// linked from the top of index.html.
void demoViewer(Report& report, const ViewSite& site);

}  // namespace pixelcloth::viz
