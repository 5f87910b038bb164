#include "pixelcloth/stitch/evaluate.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <sstream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/measure.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/stitch/seams.h"

namespace pixelcloth::stitch {

namespace {

void checkComplete(const learn::TrainedModel& model, const learn::TrainingData& data) {
  PIXELCLOTH_CHECK(model.residual() == data.residual(),
                   "predict: the model in " << model.folder().string() << (model.residual() ? " is" : " is not")
                                            << " a residual model, but its data was loaded "
                                            << (data.residual() ? "with" : "without") << " a base folder");
  if (model.architecture() != learn::Architecture::Patch) return;
  const std::vector<int> present = model.patches();
  const size_t count = patches::garmentPatches(data.garment).size();
  std::ostringstream missing;
  for (size_t id = 0, k = 0; id < count; ++id) {
    if (k < present.size() && present[k] == static_cast<int>(id)) {
      ++k;
      continue;
    }
    missing << (missing.tellp() > 0 ? "," : "") << id;
  }
  PIXELCLOTH_CHECK(missing.str().empty(), model.folder().string()
                                              << ": the garment needs all " << count << " patch decoders; "
                                              << "missing: " << missing.str() << " (train them with --patches "
                                              << missing.str() << " --out " << model.folder().string() << ")");
}

/// The networks' predictions of `chunk` (at most 16 rows at a time).
std::vector<learn::NetworkPrediction> predictChunk(const learn::TrainedModel& model, const learn::TrainingData& data,
                                                   const std::vector<int>& chunk) {
  Eigen::MatrixXf inputs(chunk.size(), data.inputs.cols());
  for (size_t k = 0; k < chunk.size(); ++k) {
    PIXELCLOTH_CHECK(chunk[k] >= 0 && chunk[k] < data.rows(),
                     "predict: row " << chunk[k] << " of a dataset of " << data.rows());
    inputs.row(static_cast<Eigen::Index>(k)) = data.inputs.row(chunk[k]);
  }
  return model.predict(inputs);
}

/// Row `k` of batch x 3 #V values as #V x 3.
Eigen::MatrixX3f vertexRows(const Eigen::MatrixXf& values, Eigen::Index k, int V) {
  Eigen::MatrixX3f out(V, 3);
  for (int v = 0; v < V; ++v) out.row(v) = values.block<1, 3>(k, 3 * v);
  return out;
}

/// The stitched garments of a chunk: assembled, base added, refined; (values, positions) per row.
void stitchChunk(const Stitcher* stitcher, const std::vector<learn::NetworkPrediction>& predictions,
                 const learn::TrainingData& data, const std::vector<int>& chunk, RowPredictions& out) {
  const int V = data.garment.mesh.numVertices();
  Eigen::MatrixXf assembled = stitcher ? stitcher->assemble(predictions) : assembleMean(predictions, V);
  if (data.residual())
    for (size_t k = 0; k < chunk.size(); ++k)
      for (int v = 0; v < V; ++v)
        assembled.block<1, 3>(static_cast<Eigen::Index>(k), 3 * v) += data.base[chunk[k]].row(v);
  if (stitcher) assembled = stitcher->refine(assembled);
  for (size_t k = 0; k < chunk.size(); ++k) {
    Eigen::MatrixX3f values = vertexRows(assembled, static_cast<Eigen::Index>(k), V);
    out.rows.push_back(chunk[k]);
    out.positions.push_back(learn::positionsFromValues(data.space, data.frames[chunk[k]], values));
    out.values.push_back(std::move(values));
  }
}

/// Running sums of one stitch mode's errors over a split.
struct Tally {
  explicit Tally(const SeamLayout& layout, int V) : seams(layout), vertexErrorCm(Eigen::VectorXd::Zero(V)) {}
  SeamMetrics seams;
  Eigen::VectorXd vertexErrorCm;
  double cosine = 0, maxError = 0;
  std::vector<Eigen::MatrixX3f> positions;
};

}  // namespace

std::vector<Eigen::MatrixX3d> separatePositions(const std::vector<learn::NetworkPrediction>& predictions,
                                                learn::OffsetSpace space, const garment::EmbeddedFrames& frames,
                                                const Eigen::MatrixXf* base, Eigen::Index k) {
  std::vector<Eigen::MatrixX3d> out;
  for (const learn::NetworkPrediction& p : predictions) {
    PIXELCLOTH_CHECK(k >= 0 && k < p.values.rows(), "separate positions: row " << k << " of " << p.values.rows());
    // Only the network's own vertices, through their own frames.
    const auto n = static_cast<Eigen::Index>(p.vertices.size());
    garment::EmbeddedFrames own{Eigen::MatrixX3d(n, 3), Eigen::MatrixX3d(n, 3), Eigen::MatrixX3d(n, 3),
                                Eigen::MatrixX3d(n, 3)};
    Eigen::MatrixX3f values(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      const int v = p.vertices[i];
      own.origin.row(i) = frames.origin.row(v);
      own.t.row(i) = frames.t.row(v);
      own.b.row(i) = frames.b.row(v);
      own.n.row(i) = frames.n.row(v);
      values.row(i) = p.values.block<1, 3>(k, 3 * i);
      if (base) values.row(i) += base->row(v);
    }
    out.push_back(learn::positionsFromValues(space, own, values));
  }
  return out;
}

RowPredictions predictRows(const learn::TrainedModel& model, const learn::TrainingData& data,
                           const std::vector<int>& rows, const Stitcher* stitcher, bool measureSeamGaps) {
  checkComplete(model, data);
  RowPredictions out;
  std::unique_ptr<SeamLayout> layout;
  if (measureSeamGaps && model.architecture() == learn::Architecture::Patch)
    layout = std::make_unique<SeamLayout>(data.garment);
  for (size_t first = 0; first < rows.size(); first += 16) {
    const std::vector<int> chunk(rows.begin() + first, rows.begin() + std::min(rows.size(), first + 16));
    const std::vector<learn::NetworkPrediction> predictions = predictChunk(model, data, chunk);
    for (size_t k = 0; measureSeamGaps && k < chunk.size(); ++k) {
      if (!layout) {
        out.seamGapCm.push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      const std::vector<Eigen::MatrixX3d> separate =
          separatePositions(predictions, data.space, data.frames[chunk[k]],
                            data.residual() ? &data.base[chunk[k]] : nullptr, static_cast<Eigen::Index>(k));
      std::vector<PredictedPositions> parts;
      for (size_t p = 0; p < predictions.size(); ++p) parts.push_back({&predictions[p].vertices, separate[p]});
      out.seamGapCm.push_back(meanSeamGapCm(*layout, parts));
    }
    stitchChunk(stitcher, predictions, data, chunk, out);
  }
  return out;
}

double Evaluation::vertexErrorQuantileCm(double q) const {
  PIXELCLOTH_CHECK(vertexErrorCm.size() > 0 && q >= 0 && q <= 1, "evaluation: quantile " << q << " of no errors");
  Eigen::VectorXd sorted = vertexErrorCm;
  std::sort(sorted.data(), sorted.data() + sorted.size());
  return sorted(static_cast<Eigen::Index>(q * (sorted.size() - 1)));
}

std::vector<Evaluation> evaluate(const learn::TrainedModel& model, const learn::TrainingData& data, data::Split split,
                                 const std::vector<const Stitcher*>& stitchers) {
  const std::vector<int>& rows = data.split(split);
  const std::string splitLabel = data::splitName(split);
  PIXELCLOTH_CHECK(!rows.empty(), "evaluate: " << data.folder.string() << " has no " << splitLabel << " samples");
  checkComplete(model, data);
  const std::vector<const Stitcher*> modes = stitchers.empty() ? std::vector<const Stitcher*>{nullptr} : stitchers;
  const core::Mesh& mesh = data.garment.mesh;
  const int V = mesh.numVertices();
  const SeamLayout layout(data.garment);
  std::vector<Tally> tallies;
  for (size_t m = 0; m < modes.size(); ++m) tallies.emplace_back(layout, V);
  double baseError = 0;
  core::Progress progress("evaluate " + splitLabel, static_cast<std::int64_t>(rows.size()));
  for (size_t first = 0; first < rows.size(); first += 16) {
    const std::vector<int> chunk(rows.begin() + first, rows.begin() + std::min(rows.size(), first + 16));
    const std::vector<learn::NetworkPrediction> predictions = predictChunk(model, data, chunk);
    std::vector<std::vector<Eigen::MatrixX3d>> separate;
    if (model.architecture() == learn::Architecture::Patch)
      for (size_t k = 0; k < chunk.size(); ++k)
        separate.push_back(separatePositions(predictions, data.space, data.frames[chunk[k]],
                                             data.residual() ? &data.base[chunk[k]] : nullptr,
                                             static_cast<Eigen::Index>(k)));
    for (size_t m = 0; m < modes.size(); ++m) {
      RowPredictions predicted;
      stitchChunk(modes[m], predictions, data, chunk, predicted);
      Tally& tally = tallies[m];
      for (size_t k = 0; k < chunk.size(); ++k) {
        tally.positions.push_back(predicted.positions[k].cast<float>());
        const Eigen::MatrixX3d truth = data.truth[chunk[k]].cast<double>();
        const Eigen::VectorXd error = 100 * (predicted.positions[k] - truth).rowwise().norm();
        tally.vertexErrorCm += error;
        tally.maxError = std::max(tally.maxError, error.maxCoeff());
        const Eigen::MatrixX3d a = core::vertexNormals(predicted.positions[k], mesh.F),
                               b = core::vertexNormals(truth, mesh.F);
        tally.cosine += (a.array() * b.array()).rowwise().sum().mean();
        std::vector<PredictedPositions> parts;
        if (!separate.empty())
          for (size_t p = 0; p < predictions.size(); ++p) parts.push_back({&predictions[p].vertices, separate[k][p]});
        tally.seams.add(parts, predicted.positions[k], truth);
      }
    }
    if (data.residual())
      for (int row : chunk) {
        const Eigen::MatrixX3d truth = data.truth[row].cast<double>();
        const Eigen::MatrixX3d base = learn::positionsFromValues(data.space, data.frames[row], data.base[row]);
        baseError += core::meanVertexErrorCm(base, truth);
      }
    progress.advance(static_cast<std::int64_t>(chunk.size()));
  }
  progress.finish();
  const double n = static_cast<double>(rows.size());
  std::vector<Evaluation> out;
  for (size_t m = 0; m < modes.size(); ++m) {
    Evaluation evaluation;
    if (modes[m]) evaluation.mode = modes[m]->mode();
    evaluation.vertexErrorCm = tallies[m].vertexErrorCm / n;
    evaluation.rows = rows;
    evaluation.positions = std::move(tallies[m].positions);
    nlohmann::json patchList = nlohmann::json::array();
    for (const patches::Patch& patch : patches::garmentPatches(data.garment)) {
      double sum = 0;
      for (int v : patch.vertices) sum += evaluation.vertexErrorCm(v);
      patchList.push_back({{"id", patch.id},
                           {"layout", data.garment.layouts[patch.layout]},
                           {"vertices", patch.vertices.size()},
                           {"vertex_error_cm", sum / patch.vertices.size()}});
    }
    const double cosine = tallies[m].cosine / n;
    evaluation.metrics = {{"split", splitLabel},
                          {"samples", rows.size()},
                          {"stitch", evaluation.mode.name()},
                          {"vertex_error_cm", evaluation.vertexErrorCm.mean()},
                          {"max_vertex_error_cm", tallies[m].maxError},
                          {"normal_cosine", cosine},
                          {"normal_cosine_distance", 1 - cosine},
                          {"base_vertex_error_cm", data.residual() ? nlohmann::json(baseError / n) : nlohmann::json()},
                          {"patches", patchList},
                          {"seams", tallies[m].seams.toJson()}};
    out.push_back(std::move(evaluation));
  }
  return out;
}

int bestPcaMode(const std::vector<Evaluation>& evaluations) {
  int best = -1;
  for (size_t i = 0; i < evaluations.size(); ++i)
    if (evaluations[i].mode.kind == StitchKind::Pca &&
        (best < 0 || evaluations[i].metrics["vertex_error_cm"].get<double>() <
                         evaluations[best].metrics["vertex_error_cm"].get<double>()))
      best = static_cast<int>(i);
  return best;
}

void writePredictions(const std::filesystem::path& folder, const Evaluation& evaluation,
                      const learn::TrainingData& data, nlohmann::json& metrics) {
  metrics["rows"] = nlohmann::json::array();
  std::vector<float> values;
  for (size_t k = 0; k < evaluation.rows.size(); ++k) {
    metrics["rows"].push_back(data.info.settings.first() + evaluation.rows[k]);
    const Eigen::MatrixX3f& p = evaluation.positions[k];
    for (Eigen::Index v = 0; v < p.rows(); ++v) values.insert(values.end(), {p(v, 0), p(v, 1), p(v, 2)});
  }
  core::writeNpy(folder / "predictions.npy", values,
                 {static_cast<std::int64_t>(evaluation.rows.size()), data.garment.mesh.numVertices(), 3});
}

}  // namespace pixelcloth::stitch
