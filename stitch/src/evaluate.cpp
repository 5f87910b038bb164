#include "pixelcloth/stitch/evaluate.h"

#include <algorithm>
#include <sstream>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh.h"
#include "pixelcloth/patches/patch.h"
#include "pixelcloth/stitch/assemble.h"

namespace pixelcloth::stitch {

RowPredictions predictRows(const learn::TrainedModel& model, const learn::TrainingData& data,
                           const std::vector<int>& rows) {
  PIXELCLOTH_CHECK(model.residual() == data.residual(),
                   "predict: the model in " << model.folder().string() << (model.residual() ? " is" : " is not")
                                            << " a residual model, but its data was loaded "
                                            << (data.residual() ? "with" : "without") << " a base folder");
  const int V = data.garment.mesh.numVertices();
  if (model.architecture() == learn::Architecture::Patch) {
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
  RowPredictions out;
  for (size_t first = 0; first < rows.size(); first += 16) {
    const std::vector<int> chunk(rows.begin() + first, rows.begin() + std::min(rows.size(), first + 16));
    Eigen::MatrixXf inputs(chunk.size(), data.inputs.cols());
    for (size_t k = 0; k < chunk.size(); ++k) {
      PIXELCLOTH_CHECK(chunk[k] >= 0 && chunk[k] < data.rows(),
                       "predict: row " << chunk[k] << " of a dataset of " << data.rows());
      inputs.row(k) = data.inputs.row(chunk[k]);
    }
    const Eigen::MatrixXf assembled = assembleMean(model.predict(inputs), V);
    for (size_t k = 0; k < chunk.size(); ++k) {
      Eigen::MatrixX3f values(V, 3);
      for (int v = 0; v < V; ++v) values.row(v) = assembled.block<1, 3>(k, 3 * v);
      if (data.residual()) values += data.base[chunk[k]];
      out.rows.push_back(chunk[k]);
      out.positions.push_back(learn::positionsFromValues(data.space, data.frames[chunk[k]], values));
      out.values.push_back(std::move(values));
    }
  }
  return out;
}

double Evaluation::vertexErrorQuantileCm(double q) const {
  PIXELCLOTH_CHECK(vertexErrorCm.size() > 0 && q >= 0 && q <= 1, "evaluation: quantile " << q << " of no errors");
  Eigen::VectorXd sorted = vertexErrorCm;
  std::sort(sorted.data(), sorted.data() + sorted.size());
  return sorted(static_cast<Eigen::Index>(q * (sorted.size() - 1)));
}

Evaluation evaluate(const learn::TrainedModel& model, const learn::TrainingData& data, const std::string& split) {
  const std::vector<int>& rows = data.split(split);
  PIXELCLOTH_CHECK(!rows.empty(), "evaluate: " << data.folder.string() << " has no " << split << " samples");
  const RowPredictions predicted = predictRows(model, data, rows);
  const core::Mesh& mesh = data.garment.mesh;
  const int V = mesh.numVertices();
  Evaluation evaluation;
  evaluation.vertexErrorCm = Eigen::VectorXd::Zero(V);
  double cosine = 0, maxError = 0, baseError = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    const Eigen::MatrixX3d truth = data.truth[rows[k]].cast<double>();
    const Eigen::VectorXd error = 100 * (predicted.positions[k] - truth).rowwise().norm();
    evaluation.vertexErrorCm += error;
    maxError = std::max(maxError, error.maxCoeff());
    const Eigen::MatrixX3d a = core::vertexNormals(predicted.positions[k], mesh.F),
                           b = core::vertexNormals(truth, mesh.F);
    cosine += (a.array() * b.array()).rowwise().sum().mean();
    if (data.residual()) {
      const Eigen::MatrixX3d base = learn::positionsFromValues(data.space, data.frames[rows[k]], data.base[rows[k]]);
      baseError += 100 * (base - truth).rowwise().norm().mean();
    }
  }
  const double n = static_cast<double>(rows.size());
  evaluation.vertexErrorCm /= n;
  nlohmann::json patchList = nlohmann::json::array();
  for (const patches::Patch& patch : patches::garmentPatches(data.garment)) {
    double sum = 0;
    for (int v : patch.vertices) sum += evaluation.vertexErrorCm(v);
    patchList.push_back({{"id", patch.id},
                         {"layout", data.garment.layouts[patch.layout]},
                         {"vertices", patch.vertices.size()},
                         {"vertex_error_cm", sum / patch.vertices.size()}});
  }
  evaluation.metrics = {{"split", split},
                        {"samples", rows.size()},
                        {"vertex_error_cm", evaluation.vertexErrorCm.mean()},
                        {"max_vertex_error_cm", maxError},
                        {"normal_cosine", cosine / n},
                        {"normal_cosine_distance", 1 - cosine / n},
                        {"base_vertex_error_cm", data.residual() ? nlohmann::json(baseError / n) : nlohmann::json()},
                        {"patches", patchList}};
  return evaluation;
}

}  // namespace pixelcloth::stitch
