#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace pixelcloth::core {

/// A float32 image with any number of named channels (cloth images: "front.du", ..., "mask").
/// Every channel is a `height x width` matrix, row 0 the top row of the picture, column 0 the left column.
struct ExrImage {
  int width = 0;
  int height = 0;
  std::vector<std::string> channelNames;  ///< one per channel, unique, in the order of `channels`
  std::vector<Eigen::MatrixXf> channels;  ///< each height x width
  std::string source;                     ///< the file it was read from, for messages; empty when built in memory

  /// The channel called `name`; throws `InputError` naming it (and `source`) and listing the channels present.
  const Eigen::MatrixXf& channel(const std::string& name) const;
  /// Whether a channel called `name` exists.
  bool hasChannel(const std::string& name) const;
  /// Appends a channel. The first channel sets width and height (values.cols() x values.rows()); later ones must
  /// match them. Throws `InputError` for an empty or repeated name, an empty matrix, or a size mismatch.
  void addChannel(const std::string& name, Eigen::MatrixXf values);
};

/// Writes `image` as a scanline OpenEXR file, every channel FLOAT, ZIP compression, channel names kept, atomically
/// (temporary name, then rename). Throws `InputError` for an image without channels or with inconsistent sizes.
void writeExr(const std::filesystem::path& path, const ExrImage& image);

/// Reads every channel of a scanline or tiled OpenEXR file as float32 (HALF and UINT channels are converted).
/// The channels come back in OpenEXR's order, which sorts them by name. Throws `InputError` naming the file when it
/// is missing, not an OpenEXR file, corrupted or truncated, or uses subsampled channels.
ExrImage readExr(const std::filesystem::path& path);

}  // namespace pixelcloth::core
