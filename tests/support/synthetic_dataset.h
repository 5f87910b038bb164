#pragma once

// A small dataset written without simulating: for tests that train networks on it.

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/data/dataset.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/garment/garment.h"
#include "support/body_fixtures.h"

namespace pixelcloth::testing {

/// `count` samples of garment `name` on the coarse mannequin, seed 5 (its splits), in a fresh folder named after
/// `tag`: small poses, the rest offsets plus a sample's own bulge.
inline std::filesystem::path syntheticDataset(const std::string& tag, const std::string& name, int count) {
  namespace fs = std::filesystem;
  namespace pb = pixelcloth::body;
  namespace pd = pixelcloth::data;
  namespace pg = pixelcloth::garment;
  const fs::path dir =
      fs::temp_directory_path() / "pixelcloth-tests" / (tag + "-" + name + "." + std::to_string(::getpid()));
  fs::remove_all(dir);
  const pb::Body& body = coarseMannequin();
  const pg::Garment garment = pg::makeGarment(name, "test");
  const int poseSize = garment.traits.poseSize();
  const Eigen::MatrixX3d rest = garment.mesh.V;
  Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(rest.rows(), 3);
  u.col(0).setOnes();
  const pg::Embedding embedding = pg::embedClosest(body.mesh.V, body.mesh.F, rest, u);
  const Eigen::MatrixX3d restOffsets =
      pg::offsetsFromPositions(pg::embeddedFrames(body.mesh.V, body.mesh.F, embedding), rest);
  pd::DatasetSettings settings;
  settings.garment = name;
  settings.poseSize = poseSize;
  settings.vertexCount = garment.mesh.numVertices();
  settings.seed = 5;
  settings.count = count;
  settings.body = {{"kind", "mannequin"}, {"edge_length", 0.02}};
  pd::DatasetWriter writer(dir, settings, body, garment, rest, embedding);
  for (int i : writer.pending()) {
    const Eigen::VectorXf vector = pb::randomPose(40 + i, 0.2).toVector().head(poseSize);
    const pb::Pose pose = pb::Pose::fromLeading(vector);
    Eigen::MatrixX3d offsets = restOffsets;
    for (int v = 0; v < offsets.rows(); ++v) offsets(v, 2) += 0.01 * std::sin(8 * rest(v, 1) + i);
    const pg::EmbeddedFrames frames = pg::embeddedFrames(body.posedVertices(pose), body.mesh.F, embedding);
    pd::Sample sample;
    sample.pose = vector;
    sample.positions = pg::positionsFromOffsets(frames, offsets).cast<float>();
    sample.offsets = pg::offsetsFromPositions(frames, sample.positions.cast<double>()).cast<float>();
    writer.add(i, sample);
  }
  writer.finish();
  return dir;
}

}  // namespace pixelcloth::testing
