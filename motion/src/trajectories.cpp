#include "pixelcloth/motion/trajectories.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/csv.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/npy.h"

namespace pixelcloth::motion {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

/// Every marker of every frame is either seen (three finite numbers) or not (three NaN).
void checkFrames(const MarkerTrajectories& t) {
  for (int f = 0; f < t.numFrames(); ++f)
    for (int m = 0; m < t.markers(); ++m) {
      const Eigen::RowVector3d p = t.frames[f].row(m);
      const int nans = p.array().isNaN().count();
      PIXELCLOTH_CHECK(!p.array().isInf().any(),
                       t.source << ": frame " << f + 1 << ", marker " << m + 1 << " is infinite, expected metres");
      PIXELCLOTH_CHECK(nans == 0 || nans == 3, t.source << ": frame " << f + 1 << ", marker " << m + 1 << " has "
                                                        << nans
                                                        << " of its 3 coordinates NaN; a marker not "
                                                           "seen in a frame has all three NaN");
    }
}

MarkerTrajectories readNpyTrajectories(const fs::path& path, int markers, const std::string& markersName) {
  const std::string file = path.string();
  // Shape and dtype from the header, before the data is read.
  const core::NpyHeader header = core::readNpyHeader(path);
  const std::vector<std::int64_t>& shape = header.shape;
  const bool threeD = shape.size() == 3 && shape[1] == markers && shape[2] == 3;
  const bool twoD = shape.size() == 2 && shape[1] == 3 * static_cast<std::int64_t>(markers);
  PIXELCLOTH_CHECK(threeD || twoD, file << ": shape " << header.shapeString() << ", expected (frames, " << markers
                                        << ", 3) or (frames, " << 3 * markers << "): the " << markers << " markers of "
                                        << markersName);
  PIXELCLOTH_CHECK(shape[0] > 0, file << ": no frames");
  const bool single = header.dtype == "<f4";
  PIXELCLOTH_CHECK(single || header.dtype == "<f8", file << ": dtype " << header.dtype << ", expected <f4 or <f8");
  const core::NpyArray array = core::readNpy(path);
  MarkerTrajectories out;
  out.source = file;
  const std::int64_t frames = shape[0];
  const float* f32 = single ? array.data<float>() : nullptr;
  const double* f64 = single ? nullptr : array.data<double>();
  for (std::int64_t f = 0; f < frames; ++f) {
    Eigen::MatrixX3d frame(markers, 3);
    for (int m = 0; m < markers; ++m)
      for (int c = 0; c < 3; ++c) {
        const std::int64_t at = (f * markers + m) * 3 + c;
        frame(m, c) = single ? static_cast<double>(f32[at]) : f64[at];
      }
    out.frames.push_back(std::move(frame));
  }
  return out;
}

MarkerTrajectories readCsvTrajectories(const fs::path& path, int markers, const std::string& markersName) {
  const std::string file = path.string();
  std::istringstream in(core::readTextFile(path));
  MarkerTrajectories out;
  out.source = file;
  std::string line;
  bool first = true;
  for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
    line = core::trim(line);
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = core::csvFields(line);
    Eigen::VectorXd values(fields.size());
    bool numeric = true;
    for (size_t k = 0; k < fields.size() && numeric; ++k) {
      const std::string& field = fields[k];
      if (field.empty() || lower(field) == "nan") {
        values[static_cast<Eigen::Index>(k)] = kNaN;
        continue;
      }
      char* end = nullptr;
      values[static_cast<Eigen::Index>(k)] = std::strtod(field.c_str(), &end);
      numeric = end == field.c_str() + field.size();
    }
    const bool wasFirst = first;
    first = false;
    if (!numeric && wasFirst) continue;  // a header line
    const std::string where = file + ": line " + std::to_string(lineNumber);
    PIXELCLOTH_CHECK(numeric, where << ": expected " << 3 * markers
                                    << " comma-separated numbers (x, y, z of each of the " << markers << " markers of "
                                    << markersName << "; empty or nan where not seen)");
    PIXELCLOTH_CHECK(values.size() == 3 * markers, where << ": " << values.size() << " columns, expected "
                                                         << 3 * markers << ": x, y, z of each of the " << markers
                                                         << " markers of " << markersName);
    out.frames.push_back(
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(values.data(), markers, 3));
  }
  PIXELCLOTH_CHECK(!out.frames.empty(), file << ": no frames");
  return out;
}

}  // namespace

MarkerTrajectories readMarkerTrajectories(const fs::path& path, int markers, const std::string& markersName) {
  PIXELCLOTH_CHECK(markers > 0, markersName << ": no markers");
  const std::string ext = lower(path.extension().string());
  PIXELCLOTH_CHECK(ext == ".npy" || ext == ".csv",
                   path.string() << ": expected marker trajectories as .npy (frames x markers x 3) or .csv");
  MarkerTrajectories out =
      ext == ".npy" ? readNpyTrajectories(path, markers, markersName) : readCsvTrajectories(path, markers, markersName);
  checkFrames(out);
  return out;
}

void writeMarkerTrajectories(const fs::path& path, const MarkerTrajectories& trajectories) {
  const int M = trajectories.markers();
  PIXELCLOTH_CHECK(trajectories.numFrames() > 0 && M > 0, path.string() << ": no frames or no markers to write");
  std::vector<float> values;
  values.reserve(static_cast<size_t>(trajectories.numFrames()) * M * 3);
  for (const Eigen::MatrixX3d& frame : trajectories.frames) {
    PIXELCLOTH_CHECK(frame.rows() == M, path.string() << ": frames of " << frame.rows() << " and " << M << " markers");
    for (int m = 0; m < M; ++m)
      for (int c = 0; c < 3; ++c) values.push_back(static_cast<float>(frame(m, c)));
  }
  core::writeNpy(path, values, {trajectories.numFrames(), M, 3});
}

}  // namespace pixelcloth::motion
