#pragma once

// Marker trajectories: where each of a garment's markers (cage/markers.h) is in every frame of a capture, as an
// optical motion-capture system exports them. A marker the cameras lost in a frame is NaN there (dropout).

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace pixelcloth::motion {

struct MarkerTrajectories {
  std::string source;                    ///< the file read, for messages
  std::vector<Eigen::MatrixX3d> frames;  ///< per frame: M x 3 positions, metres; a row of NaN where not seen
  int markers() const { return frames.empty() ? 0 : static_cast<int>(frames.front().rows()); }
  int numFrames() const { return static_cast<int>(frames.size()); }
};

/// Reads the trajectories of `markers` markers (the marker file's count, named by `markersName` in messages):
/// - `.npy`: float32 or float64 of shape (frames, markers, 3) or (frames, 3 markers);
/// - `.csv`: one line per frame of 3 markers numbers, x y z of each marker in the marker file's order; an empty field
///   or `nan` where a marker is not seen; an optional header line and `#` comments.
/// A marker is seen in a frame when all three of its coordinates are numbers, and not seen when all three are NaN.
/// Throws InputError naming the file (and the line or frame and marker) for a missing or malformed file, no frames, a
/// count of markers other than `markers`, an infinite coordinate, or a marker with some coordinates NaN and not all.
MarkerTrajectories readMarkerTrajectories(const std::filesystem::path& path, int markers,
                                          const std::string& markersName);

/// Writes `trajectories` as a float32 .npy of shape (frames, markers, 3), NaN where not seen, atomically.
void writeMarkerTrajectories(const std::filesystem::path& path, const MarkerTrajectories& trajectories);

}  // namespace pixelcloth::motion
