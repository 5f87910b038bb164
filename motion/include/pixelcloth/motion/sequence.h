#pragma once

// Garment and body sequences out: PC2 point caches (what Blender's Mesh Cache modifier and 3ds Max read), OBJ
// sequences, and the temporal measures of a predicted sequence (the paper's future work is temporal coherence):
// jitter, the garment inside the body, over the frames.

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pixelcloth/core/mesh.h"

namespace pixelcloth::motion {

/// Writes a PC2 point cache, atomically: the 12-byte signature "POINTCACHE2\0", int32 version 1, int32 points,
/// float32 start frame, float32 sample rate (frames per sample: 1), int32 samples, then per sample each point's
/// float32 x, y, z (little endian). Every frame must have the same number of rows and finite values.
void writePc2(const std::filesystem::path& path, const std::vector<Eigen::MatrixX3d>& frames, double startFrame = 0);

/// Reads a PC2 file; InputError naming the file for a wrong signature or version, counts that disagree with its size
/// (a truncated file) or values that are not finite.
std::vector<Eigen::MatrixX3f> readPc2(const std::filesystem::path& path);

/// Writes `stem`_NNNN.obj into `folder` for every frame: `mesh` (its faces and texture coordinates) with the frame's
/// positions.
void writeObjSequence(const std::filesystem::path& folder, const std::string& stem, const core::Mesh& mesh,
                      const std::vector<Eigen::MatrixX3d>& frames);

/// Per-frame measures of a garment sequence on its body sequence, both in the body's root frame.
struct TemporalMetrics {
  double fps = 0;
  /// Mean over the vertices of |x(t+1) - 2 x(t) + x(t-1)|, cm; NaN at the first and last frames.
  std::vector<double> garmentJitterCm, bodyJitterCm;
  std::vector<int> insideVertices;  ///< garment vertices inside the closed body
  std::vector<double> maxDepthCm;   ///< the deepest of them, cm (0 when none)
  /// Per frame, where the garment came from patch networks: the mean gap between their predictions of the cage-curve
  /// vertices before blending (stitch::meanSeamGapCm), cm. Empty when not measured, NaN for a frame without it.
  std::vector<double> seamGapCm;

  double meanGarmentJitterCm() const;
  double meanBodyJitterCm() const;
  double meanSeamGapCm() const;  ///< NaN when not measured
  int framesWithInside() const;  ///< frames where some garment vertex is inside the body
  nlohmann::json toJson() const;
};

/// Measures `garment` (frames of #G x 3) against `body` (frames of #B x 3 with faces `bodyFaces`, a closed mesh).
/// Progress on stderr.
TemporalMetrics temporalMetrics(const std::vector<Eigen::MatrixX3d>& garment, const std::vector<Eigen::MatrixX3d>& body,
                                const Eigen::MatrixX3i& bodyFaces, double fps);

}  // namespace pixelcloth::motion
