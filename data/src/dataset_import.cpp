// Importing garment shapes from another simulator or from capture: OBJ sequences with poses.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>

#include "dataset_internal.h"
#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/csv.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/geometry.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// Natural order: runs of digits compare as numbers, so frame_2 comes before frame_10.
bool naturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      std::string na = a.substr(i, ei - i), nb = b.substr(j, ej - j);
      na.erase(0, std::min(na.find_first_not_of('0'), na.size()));
      nb.erase(0, std::min(nb.find_first_not_of('0'), nb.size()));
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = ei;
      j = ej;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j || (a.size() - i == b.size() - j && a < b);
}

/// A pose vector of `poseSize` floats checked to be rotations (the rest of the 90 at identity) within the joint limits:
/// beyond them refused naming `context`, or clamped (and counted in `clamped`).
Eigen::VectorXf checkedPose(const Eigen::VectorXf& values, int poseSize, const std::string& context,
                            body::BeyondLimits beyondLimits, int& clamped) {
  const body::Pose pose =
      body::Pose::fromLeading(values.head(std::min<Eigen::Index>(values.size(), poseSize)), context);
  const std::string beyond = pose.limitViolation();
  if (beyond.empty()) return values.head(poseSize);
  PIXELCLOTH_CHECK(beyondLimits == body::BeyondLimits::Clamp,
                   context << ": " << beyond << "; --clamp-to-limits clamps every pose into the limits");
  ++clamped;
  return pose.clampedToLimits().toVector().head(poseSize);
}

}  // namespace

std::vector<fs::path> objSequence(const fs::path& folder) {
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::is_directory(folder, ec), folder.string() << ": no such folder (expected a folder of OBJ "
                                                                 << "files, one garment mesh per frame)");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && ext == ".obj") files.push_back(entry.path());
  }
  PIXELCLOTH_CHECK(!files.empty(), folder.string() << ": holds no .obj files");
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return naturalLess(a.filename().string(), b.filename().string());
  });
  return files;
}

std::vector<Eigen::VectorXf> readPoseSequence(const fs::path& path, int poseSize, body::BeyondLimits beyondLimits) {
  int clamped = 0;
  PIXELCLOTH_CHECK(
      poseSize == body::kPoseSize || poseSize == body::kNecktiePoseSize,
      "poses: pose size " << poseSize << ", expected " << body::kPoseSize << " or " << body::kNecktiePoseSize);
  const std::string file = path.string();
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  // The necktie uses the first four joints; full 90-number pose vectors are accepted for it too.
  const std::string alsoFull = poseSize == body::kNecktiePoseSize
                                   ? " (or " + std::to_string(body::kPoseSize) + ", of which the first " +
                                         std::to_string(poseSize) + " are used)"
                                   : "";
  std::vector<Eigen::VectorXf> poses;
  if (ext == ".json") {
    json j = core::readJson(path);
    if (j.is_object() && j.contains("poses")) j = j["poses"];
    PIXELCLOTH_CHECK(j.is_array(), file << ": expected a list of poses (or {\"poses\": [...]})");
    for (size_t i = 0; i < j.size(); ++i) {
      const std::string context = file + ": pose " + std::to_string(i);
      const json& entry = j[i];
      if (entry.is_array()) {
        PIXELCLOTH_CHECK(
            entry.size() == static_cast<size_t>(poseSize) || entry.size() == static_cast<size_t>(body::kPoseSize),
            context << ": " << entry.size() << " numbers, expected " << poseSize << alsoFull);
        Eigen::VectorXf values(entry.size());
        for (int k = 0; k < static_cast<int>(entry.size()); ++k) {
          PIXELCLOTH_CHECK(entry[k].is_number(),
                           context << ": entry " << k << " is " << entry[k].dump() << ", expected a number");
          values[k] = entry[k].get<float>();
        }
        poses.push_back(checkedPose(values, poseSize, context, beyondLimits, clamped));
      } else {
        PIXELCLOTH_CHECK(entry.is_object(), context << ": expected a pose object or a list of " << poseSize
                                                    << " numbers, found " << entry.type_name());
        const Eigen::VectorXf values = body::poseFromJson(entry, context).toVector();
        poses.push_back(checkedPose(values, poseSize, context, beyondLimits, clamped));
      }
    }
  } else {
    std::ifstream in(path);
    PIXELCLOTH_CHECK(in, file << ": cannot open for reading");
    std::string line;
    for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
      line = core::trim(line);
      if (line.empty() || line[0] == '#') continue;
      const std::vector<std::string> fields = core::csvFields(line);
      std::vector<float> values;
      bool numeric = true;
      for (const std::string& field : fields) {
        char* end = nullptr;
        const double v = std::strtod(field.c_str(), &end);
        if (field.empty() || end != field.c_str() + field.size()) {
          numeric = false;
          break;
        }
        values.push_back(static_cast<float>(v));
      }
      const std::string context = file + ": line " + std::to_string(lineNumber);
      if (!numeric && poses.empty() && lineNumber == 1) continue;  // header row
      PIXELCLOTH_CHECK(numeric, context << ": expected " << poseSize << " comma-separated numbers");
      PIXELCLOTH_CHECK(
          values.size() == static_cast<size_t>(poseSize) || values.size() == static_cast<size_t>(body::kPoseSize),
          context << ": " << values.size() << " columns, expected " << poseSize << alsoFull);
      poses.push_back(checkedPose(Eigen::Map<const Eigen::VectorXf>(values.data(), values.size()), poseSize, context,
                                  beyondLimits, clamped));
    }
  }
  PIXELCLOTH_CHECK(!poses.empty(), file << ": no poses");
  if (clamped > 0)
    PIXELCLOTH_WARN(file << ": " << clamped << " of " << poses.size() << " poses clamped into the joint limits");
  return poses;
}

Sample detail::sampleOfPositions(const Eigen::VectorXf& pose, int poseSize, const Eigen::MatrixX3d& positions,
                                 const body::Body& body, const garment::Garment& garment,
                                 const garment::Embedding& embedding, const std::string& context) {
  const body::Pose posed = body::Pose::fromLeading(pose.head(poseSize), context);
  const garment::EmbeddedFrames frames = garment::embeddedFrames(body.posedVertices(posed), body.mesh.F, embedding);
  Sample sample;
  sample.pose = pose;
  sample.positions = positions.cast<float>();
  sample.offsets = garment::offsetsFromPositions(frames, positions).cast<float>();
  const Eigen::VectorXd ratio = core::areaRatios(positions, garment.mesh);
  sample.stats.minAreaRatio = ratio.minCoeff();
  sample.stats.maxAreaRatio = ratio.maxCoeff();
  return sample;
}

DatasetSettings importDataset(const std::vector<fs::path>& objs, const fs::path& posesFile, const body::Body& body,
                              const garment::Garment& garment, const Eigen::MatrixX3d& restPositions,
                              const garment::Embedding& embedding, const fs::path& out, const ImportOptions& options) {
  PIXELCLOTH_CHECK(!objs.empty(), "dataset import: no OBJ files");
  DatasetSettings settings;
  settings.garment = garment.name;
  settings.poseSize = garment.traits.poseSize();
  settings.vertexCount = garment.mesh.numVertices();
  settings.seed = options.seed;
  settings.count = static_cast<int>(objs.size());
  settings.body = options.body;
  settings.source = "imported";
  settings.generator = {{"objs", objs.size() == 1 ? objs.front().string() : objs.front().parent_path().string()},
                        {"poses", posesFile.string()}};
  const std::vector<Eigen::VectorXf> poses = readPoseSequence(posesFile, settings.poseSize, options.beyondLimits);
  PIXELCLOTH_CHECK(poses.size() == objs.size(), posesFile.string() << ": " << poses.size() << " poses for "
                                                                   << objs.size() << " OBJ files; expected one pose "
                                                                   << "per frame");
  core::checkOutputFolder(out);

  // Validate every frame before anything is written.
  auto readFrame = [&](int i) {
    const core::Mesh mesh = core::readMesh(objs[i]);
    PIXELCLOTH_CHECK(mesh.numVertices() == settings.vertexCount,
                     objs[i].string() << ": " << mesh.numVertices() << " vertices, but the " << garment.name << " has "
                                      << settings.vertexCount << " (same topology expected)");
    PIXELCLOTH_CHECK(mesh.numFaces() == garment.mesh.numFaces(),
                     objs[i].string() << ": " << mesh.numFaces() << " faces, but the " << garment.name << " has "
                                      << garment.mesh.numFaces() << " (same topology expected)");
    for (int f = 0; f < mesh.numFaces(); ++f) {
      const Eigen::RowVector3i a = mesh.F.row(f), b = garment.mesh.F.row(f);
      const bool same =
          a == b || a == Eigen::RowVector3i(b[1], b[2], b[0]) || a == Eigen::RowVector3i(b[2], b[0], b[1]);
      PIXELCLOTH_CHECK(same, objs[i].string()
                                 << ": face " << f + 1 << " is (" << a[0] + 1 << ", " << a[1] + 1 << ", " << a[2] + 1
                                 << "), the " << garment.name << "'s is (" << b[0] + 1 << ", " << b[1] + 1 << ", "
                                 << b[2] + 1 << ") (same vertex order and faces expected)");
    }
    return mesh.V;
  };
  {
    core::Progress progress("dataset import: checking", static_cast<std::int64_t>(objs.size()));
    for (int i = 0; i < static_cast<int>(objs.size()); ++i) {
      readFrame(i);
      progress.advance();
    }
  }

  DatasetWriter writer(out, settings, body, garment, restPositions, embedding);
  const std::vector<int> pending = writer.pending();
  core::Progress progress("dataset import", static_cast<std::int64_t>(pending.size()));
  for (int i : pending) {
    writer.add(i, detail::sampleOfPositions(poses[i], settings.poseSize, readFrame(i), body, garment, embedding,
                                            posesFile.string()));
    progress.advance();
  }
  progress.finish();
  writer.finish();
  return settings;
}

}  // namespace pixelcloth::data
