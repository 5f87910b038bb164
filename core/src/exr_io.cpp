#include "pixelcloth/core/exr_io.h"

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <exception>
#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

namespace fs = std::filesystem;

namespace {

std::string listOf(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + ("'" + name + "'");
  return list;
}

// The most values (pixels x channels) readExr allocates for.
constexpr long long kMaxExrValues = 1LL << 28;

// A slice over a column-major height x width matrix: pixel (x, y) is at data[y + x * height].
Imf::Slice sliceOf(const float* data, const Imath::Box2i& window, int height) {
  return Imf::Slice::Make(Imf::FLOAT, data, window, sizeof(float) * static_cast<size_t>(height), sizeof(float));
}

}  // namespace

const Eigen::MatrixXf& ExrImage::channel(const std::string& name) const {
  auto it = std::find(channelNames.begin(), channelNames.end(), name);
  PIXELCLOTH_CHECK(it != channelNames.end(), (source.empty() ? "image" : source)
                                                 << ": no channel '" << name << "'; the channels are "
                                                 << listOf(channelNames));
  return channels[it - channelNames.begin()];
}

bool ExrImage::hasChannel(const std::string& name) const {
  return std::find(channelNames.begin(), channelNames.end(), name) != channelNames.end();
}

void ExrImage::addChannel(const std::string& name, Eigen::MatrixXf values) {
  PIXELCLOTH_CHECK(!name.empty(), "an image channel needs a name");
  PIXELCLOTH_CHECK(!hasChannel(name), "image already has a channel '" << name << "'");
  PIXELCLOTH_CHECK(values.size() > 0, "image channel '" << name << "' is empty");
  if (channels.empty()) {
    width = static_cast<int>(values.cols());
    height = static_cast<int>(values.rows());
  }
  PIXELCLOTH_CHECK(values.cols() == width && values.rows() == height,
                   "image channel '" << name << "' is " << values.rows() << " x " << values.cols()
                                     << " (rows x columns), expected " << height << " x " << width);
  channelNames.push_back(name);
  channels.push_back(std::move(values));
}

void writeExr(const fs::path& path, const ExrImage& image) {
  const std::string file = path.string();
  PIXELCLOTH_CHECK(!image.channels.empty() && image.width > 0 && image.height > 0,
                   file << ": cannot write an image without channels or pixels");
  PIXELCLOTH_CHECK(image.channelNames.size() == image.channels.size(), file << ": " << image.channelNames.size()
                                                                            << " channel names for "
                                                                            << image.channels.size() << " channels");
  for (size_t c = 0; c < image.channels.size(); ++c) {
    const std::string& name = image.channelNames[c];
    PIXELCLOTH_CHECK(!name.empty(), file << ": channel " << c << " has no name");
    PIXELCLOTH_CHECK(std::count(image.channelNames.begin(), image.channelNames.end(), name) == 1,
                     file << ": channel name '" << name << "' is used twice");
    PIXELCLOTH_CHECK(image.channels[c].rows() == image.height && image.channels[c].cols() == image.width,
                     file << ": channel '" << name << "' is " << image.channels[c].rows() << " x "
                          << image.channels[c].cols() << ", expected " << image.height << " x " << image.width);
  }
  writeAtomically(path, [&](const fs::path& temporary) {
    try {
      Imf::Header header(image.width, image.height);
      header.compression() = Imf::ZIP_COMPRESSION;
      for (const std::string& name : image.channelNames) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      Imf::FrameBuffer frameBuffer;
      for (size_t c = 0; c < image.channels.size(); ++c) {
        frameBuffer.insert(image.channelNames[c], sliceOf(image.channels[c].data(), header.dataWindow(), image.height));
      }
      Imf::OutputFile out(temporary.c_str(), header);
      out.setFrameBuffer(frameBuffer);
      out.writePixels(image.height);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      PIXELCLOTH_FAIL(file << ": cannot write the OpenEXR file (" << e.what() << ")");
    }
  });
}

ExrImage readExr(const fs::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  PIXELCLOTH_CHECK(fs::exists(path, ec), file << ": no such file");
  PIXELCLOTH_CHECK(fs::is_regular_file(path, ec), file << ": is not a regular file");
  ExrImage image;
  image.source = file;
  try {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i window = in.header().dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    PIXELCLOTH_CHECK(width > 0 && height > 0 && width * height <= (1LL << 31),
                     file << ": unsupported image size " << width << " x " << height);
    long long numChannels = 0;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) ++numChannels;
    PIXELCLOTH_CHECK(numChannels > 0, file << ": the OpenEXR file has no channels");
    // A few bytes of header can declare any size: check before allocating (1 GiB of floats at most), and that the
    // file holds every scan line or tile it declares.
    PIXELCLOTH_CHECK(width * height * numChannels <= kMaxExrValues,
                     file << ": the image is " << width << " x " << height << " with " << numChannels
                          << " channels, more than the " << kMaxExrValues << " values (1 GiB as floats) supported");
    PIXELCLOTH_CHECK(in.isComplete(), file << ": truncated: some scan lines or tiles are missing");
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    Imf::FrameBuffer frameBuffer;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
      PIXELCLOTH_CHECK(it.channel().xSampling == 1 && it.channel().ySampling == 1,
                       file << ": channel '" << it.name() << "' is subsampled, which is not supported");
      image.channelNames.emplace_back(it.name());
      image.channels.emplace_back(Eigen::MatrixXf::Zero(image.height, image.width));
    }
    // Every channel type is read into a FLOAT slice: OpenEXR converts HALF and UINT.
    for (size_t c = 0; c < image.channels.size(); ++c) {
      frameBuffer.insert(image.channelNames[c], sliceOf(image.channels[c].data(), window, image.height));
    }
    in.setFrameBuffer(frameBuffer);
    in.readPixels(window.min.y, window.max.y);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    PIXELCLOTH_FAIL(file << ": not a readable OpenEXR file, or it is corrupted or truncated (" << e.what() << ")");
  }
  return image;
}

}  // namespace pixelcloth::core
