#pragma once

// The T-shirt dressed on the coarse mannequin, its worn shapes, and a small dataset of them: what the recon/ tests
// rebuild from markers.
#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <memory>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/cage/body_cage.h"
#include "pixelcloth/cage/dressing.h"
#include "pixelcloth/cage/garment_cage.h"
#include "pixelcloth/cage/markers.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/recon/reconstruct.h"
#include "support/fixtures.h"

namespace pixelcloth::testing {

/// The T-shirt dressed on the coarse mannequin, with a reconstructor over it.
struct Dressed {
  const body::Body& body = coarseMannequin();
  const garment::Garment& garment = tshirt();
  cage::Dressing dressing;
  std::unique_ptr<recon::GarmentReconstructor> reconstructor;
  cage::MarkerSet definition;

  Dressed() {
    dressing = cage::dressGarment(body, cage::bodyCage(body), garment, cage::garmentCage(garment));
    reconstructor = std::make_unique<recon::GarmentReconstructor>(body, garment, dressing.embedding, dressing.relaxed);
    definition = cage::defineMarkers(garment, reconstructor->cage());
  }

  /// A worn shape of the dressed shirt in `pose`: its rest offsets carried by the posed body, plus a smooth bulge.
  Eigen::MatrixX3d worn(const body::Pose& pose, double bulge) const {
    const garment::EmbeddedFrames rest = garment::embeddedFrames(body.mesh.V, body.mesh.F, dressing.embedding);
    Eigen::MatrixX3d offsets = garment::offsetsFromPositions(rest, dressing.relaxed);
    for (int v = 0; v < offsets.rows(); ++v)
      offsets(v, 2) += bulge * (1 + std::sin(4 * dressing.relaxed(v, 1)) * std::cos(5 * dressing.relaxed(v, 0)));
    const garment::EmbeddedFrames posed =
        garment::embeddedFrames(body.posedVertices(pose), body.mesh.F, dressing.embedding);
    return garment::positionsFromOffsets(posed, offsets);
  }
};

/// Built once per test process (dressing takes a few seconds).
inline const Dressed& dressed() {
  static const Dressed d;
  return d;
}

/// Writes a finished dataset of `count` worn shirts into `folder` (sample i: random pose 100 + i, bulge 2 + 0.5 i mm).
inline void writeWornDataset(const Dressed& d, const std::filesystem::path& folder, int count, std::uint64_t seed) {
  data::DatasetSettings settings;
  settings.garment = "tshirt";
  settings.poseSize = body::kPoseSize;
  settings.vertexCount = d.garment.mesh.numVertices();
  settings.seed = seed;
  settings.count = count;
  settings.body = {{"kind", "mannequin"}, {"edge_length", 0.02}};
  data::DatasetWriter writer(folder, settings, d.body, d.garment, d.dressing.relaxed, d.dressing.embedding);
  for (int i : writer.pending()) {
    const body::Pose pose = body::randomPose(100 + i, 0.3);
    const Eigen::MatrixX3d positions = d.worn(pose, 0.002 + 0.0005 * i);
    const garment::EmbeddedFrames frames =
        garment::embeddedFrames(d.body.posedVertices(pose), d.body.mesh.F, d.dressing.embedding);
    data::Sample sample;
    sample.pose = pose.toVector();
    sample.positions = positions.cast<float>();
    sample.offsets = garment::offsetsFromPositions(frames, positions).cast<float>();
    writer.add(i, sample);
  }
  writer.finish();
}

}  // namespace pixelcloth::testing
