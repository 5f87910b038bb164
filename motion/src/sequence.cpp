#include "pixelcloth/motion/sequence.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/mesh_index.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/core/parallel.h"
#include "pixelcloth/core/progress.h"

namespace pixelcloth::motion {

namespace fs = std::filesystem;

namespace {
constexpr char kPc2Signature[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr std::size_t kPc2Header = 32;

template <typename T>
void put(std::string& bytes, T value) {
  static_assert(sizeof(T) == 4, "PC2 fields are 4 bytes");
  char raw[4];
  std::memcpy(raw, &value, 4);  // little endian on every machine pixelcloth builds for
  bytes.append(raw, 4);
}

template <typename T>
T get(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

double mean(const std::vector<double>& values) {
  double sum = 0;
  int n = 0;
  for (double v : values)
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  return n ? sum / n : std::nan("");
}

/// |x(t+1) - 2 x(t) + x(t-1)| averaged over the vertices, cm, per frame (NaN at both ends).
std::vector<double> jitterCm(const std::vector<Eigen::MatrixX3d>& frames) {
  std::vector<double> out(frames.size(), std::nan(""));
  for (size_t t = 1; t + 1 < frames.size(); ++t)
    out[t] = 100 * (frames[t + 1] - 2 * frames[t] + frames[t - 1]).rowwise().norm().mean();
  return out;
}
}  // namespace

void writePc2(const fs::path& path, const std::vector<Eigen::MatrixX3d>& frames, double startFrame) {
  PIXELCLOTH_CHECK(!frames.empty(), path.string() << ": a point cache of no frames");
  const Eigen::Index points = frames.front().rows();
  std::string bytes(kPc2Signature, sizeof(kPc2Signature));
  put<std::int32_t>(bytes, 1);
  put<std::int32_t>(bytes, static_cast<std::int32_t>(points));
  put<float>(bytes, static_cast<float>(startFrame));
  put<float>(bytes, 1.0f);
  put<std::int32_t>(bytes, static_cast<std::int32_t>(frames.size()));
  bytes.reserve(kPc2Header + frames.size() * points * 12);
  for (size_t f = 0; f < frames.size(); ++f) {
    PIXELCLOTH_CHECK(frames[f].rows() == points && frames[f].allFinite(),
                     path.string() << ": frame " << f << " has " << frames[f].rows() << " points (expected " << points
                                   << ") or values that are not finite");
    for (Eigen::Index i = 0; i < points; ++i)
      for (int c = 0; c < 3; ++c) put<float>(bytes, static_cast<float>(frames[f](i, c)));
  }
  core::writeTextAtomically(path, bytes);
}

std::vector<Eigen::MatrixX3f> readPc2(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  PIXELCLOTH_CHECK(in, path.string() << ": cannot open the point cache");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string file = path.string();
  PIXELCLOTH_CHECK(bytes.size() >= kPc2Header && std::memcmp(bytes.data(), kPc2Signature, 12) == 0,
                   file << ": not a PC2 point cache (expected the signature POINTCACHE2)");
  const auto version = get<std::int32_t>(bytes, 12), points = get<std::int32_t>(bytes, 16),
             samples = get<std::int32_t>(bytes, 28);
  PIXELCLOTH_CHECK(version == 1, file << ": PC2 version " << version << ", expected 1");
  PIXELCLOTH_CHECK(points >= 0 && samples >= 0, file << ": " << points << " points, " << samples << " samples");
  const std::uint64_t expected = kPc2Header + static_cast<std::uint64_t>(points) * samples * 12;
  PIXELCLOTH_CHECK(bytes.size() == expected, file << ": " << bytes.size() << " bytes, expected " << expected << " for "
                                                  << samples << " samples of " << points << " points (truncated?)");
  std::vector<Eigen::MatrixX3f> frames(samples, Eigen::MatrixX3f(points, 3));
  std::size_t at = kPc2Header;
  for (int f = 0; f < samples; ++f)
    for (int i = 0; i < points; ++i)
      for (int c = 0; c < 3; ++c, at += 4) {
        frames[f](i, c) = get<float>(bytes, at);
        PIXELCLOTH_CHECK(std::isfinite(frames[f](i, c)),
                         file << ": sample " << f << ", point " << i << " is not finite");
      }
  return frames;
}

void writeObjSequence(const fs::path& folder, const std::string& stem, const core::Mesh& mesh,
                      const std::vector<Eigen::MatrixX3d>& frames) {
  if (frames.empty()) return;
  for (size_t f = 0; f < frames.size(); ++f)
    PIXELCLOTH_CHECK(frames[f].rows() == mesh.V.rows() && frames[f].allFinite(),
                     (folder / stem).string()
                         << ": frame " << f << " has " << frames[f].rows() << " positions or some not finite; expected "
                         << mesh.V.rows() << " finite ones, one per vertex");
  auto pathOf = [&](size_t f) {
    char name[32];
    std::snprintf(name, sizeof(name), "_%04zu.obj", f);
    return folder / (stem + name);
  };
  // The first frame through the OBJ writer (OpenMesh's); every other frame is that file with its vertex lines
  // replaced, since the faces and texture coordinates do not change.
  core::Mesh posed = mesh;
  posed.V = frames.front();
  core::writeMesh(pathOf(0), posed);
  const std::string first = core::readTextFile(pathOf(0));
  std::vector<size_t> starts;  // where each "v " line starts
  for (size_t at = 0; at < first.size(); at = first.find('\n', at) + 1) {
    if (first.compare(at, 2, "v ") == 0) starts.push_back(at);
    if (first.find('\n', at) == std::string::npos) break;
  }
  const auto V = static_cast<size_t>(mesh.V.rows());
  bool contiguous = starts.size() == V;
  for (size_t i = 1; contiguous && i < V; ++i) contiguous = first.find('\n', starts[i - 1]) + 1 == starts[i];
  if (!contiguous) {  // a layout this shortcut does not know: the writer for every frame
    for (size_t f = 1; f < frames.size(); ++f) {
      posed.V = frames[f];
      core::writeMesh(pathOf(f), posed);
    }
    return;
  }
  const std::string head = first.substr(0, starts.front());
  const std::string tail = first.substr(first.find('\n', starts.back()) + 1);
  core::parallelFor(static_cast<int>(frames.size()) - 1, 0, [&](int k) {
    const Eigen::MatrixX3d& P = frames[k + 1];
    std::string text = head;
    text.reserve(head.size() + tail.size() + V * 40);
    char buffer[32];
    for (size_t i = 0; i < V; ++i) {
      text += "v";
      for (int c = 0; c < 3; ++c) {
        const auto end = std::to_chars(buffer, buffer + sizeof(buffer), P(static_cast<Eigen::Index>(i), c),
                                       std::chars_format::general, 9);
        text += ' ';
        text.append(buffer, end.ptr);
      }
      text += '\n';
    }
    text += tail;
    core::writeTextAtomically(pathOf(k + 1), text);
  });
}

double TemporalMetrics::meanGarmentJitterCm() const { return mean(garmentJitterCm); }
double TemporalMetrics::meanBodyJitterCm() const { return mean(bodyJitterCm); }
double TemporalMetrics::meanSeamGapCm() const { return mean(seamGapCm); }
int TemporalMetrics::framesWithInside() const {
  int n = 0;
  for (int count : insideVertices) n += count > 0;
  return n;
}

nlohmann::json TemporalMetrics::toJson() const {
  auto finite = [](const std::vector<double>& values) {
    nlohmann::json out = nlohmann::json::array();
    for (double v : values) out.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json());
    return out;
  };
  double deepest = 0;
  for (double d : maxDepthCm) deepest = std::max(deepest, d);
  const double gap = meanSeamGapCm();
  nlohmann::json seamGap;  // null when not measured
  if (!seamGapCm.empty())
    seamGap = {{"mean", std::isfinite(gap) ? nlohmann::json(gap) : nlohmann::json()}, {"per_frame", finite(seamGapCm)}};
  return {{"fps", fps},
          {"frames", insideVertices.size()},
          {"garment_jitter_cm", {{"mean", meanGarmentJitterCm()}, {"per_frame", finite(garmentJitterCm)}}},
          {"body_jitter_cm", {{"mean", meanBodyJitterCm()}, {"per_frame", finite(bodyJitterCm)}}},
          {"inside_body",
           {{"frames_with_any", framesWithInside()},
            {"max_depth_cm", deepest},
            {"vertices_per_frame", insideVertices},
            {"max_depth_cm_per_frame", maxDepthCm}}},
          {"seam_gap_cm", seamGap}};
}

TemporalMetrics temporalMetrics(const std::vector<Eigen::MatrixX3d>& garment, const std::vector<Eigen::MatrixX3d>& body,
                                const Eigen::MatrixX3i& bodyFaces, double fps) {
  PIXELCLOTH_CHECK(!garment.empty() && garment.size() == body.size(),
                   "temporal metrics: " << garment.size() << " garment frames and " << body.size() << " body frames");
  TemporalMetrics metrics;
  metrics.fps = fps;
  metrics.garmentJitterCm = jitterCm(garment);
  metrics.bodyJitterCm = jitterCm(body);
  const int frames = static_cast<int>(garment.size());
  metrics.insideVertices.assign(frames, 0);
  metrics.maxDepthCm.assign(frames, 0);
  core::Progress progress("inside the body", frames);
  // Contiguous runs of frames per thread, so that each query starts from the closest point of the frame before (the
  // body moves little between frames): CGAL's search then prunes early.
  const int threads = core::threadCount(0, frames);
  core::parallelFor(threads, threads, [&](int t) {
    std::vector<core::MeshHit> previous;
    for (int f = t * frames / threads; f < (t + 1) * frames / threads; ++f) {
      const core::MeshIndex index(body[f], bodyFaces);
      const Eigen::MatrixX3d& P = garment[f];
      previous.resize(P.rows());
      for (Eigen::Index i = 0; i < P.rows(); ++i) {
        const Eigen::Vector3d p = P.row(i).transpose();
        core::MeshHit hit;
        if (previous[i].face < 0) {
          hit = index.closest(p);
        } else {
          core::MeshHit near = previous[i];
          near.point = Eigen::Vector3d::Zero();
          for (int k = 0; k < 3; ++k)
            near.point += near.barycentric(k) * body[f].row(bodyFaces(near.face, k)).transpose();
          hit = index.closest(p, near);
        }
        previous[i] = hit;
        if (!index.inside(p, hit)) continue;
        ++metrics.insideVertices[f];
        metrics.maxDepthCm[f] = std::max(metrics.maxDepthCm[f], 100 * hit.distance);
      }
      progress.advance();
    }
  });
  progress.finish();
  return metrics;
}

}  // namespace pixelcloth::motion
