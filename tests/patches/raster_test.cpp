// Raster and sample operators between cloth pixels and cloth images, on the built-in T-shirt.
#include "pixelcloth/patches/raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>

#include "pixelcloth/garment/garment.h"
#include "pixelcloth/patches/frame.h"
#include "support/fixtures.h"
#include "support/test_util.h"

namespace pp = pixelcloth::patches;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;
using pixelcloth::testing::freshDir;
using pixelcloth::testing::inputErrorOf;

namespace {
const pixelcloth::garment::Garment& shirt() { return pixelcloth::testing::tshirt(); }

using Field = std::function<double(const Eigen::Vector2d&)>;

/// Per-vertex values of `field` evaluated at each vertex's UV in `layout` (0 for vertices not in it), #V x 3: the
/// field, 2 * field, and -field.
Eigen::MatrixXf vertexField(const pg::Garment& g, int layout, const Field& field) {
  Eigen::MatrixXf x = Eigen::MatrixXf::Zero(g.mesh.numVertices(), 3);
  for (int v = 0; v < g.mesh.numVertices(); ++v) {
    int row = g.vertexUV(v, layout);
    if (row < 0) continue;
    double f = field(g.mesh.UV.row(row).transpose());
    x.row(v) << f, 2 * f, -f;
  }
  return x;
}

/// Field value range over the layout's vertices.
double rangeOf(const Eigen::MatrixXf& x, const std::vector<int>& vertices) {
  double lo = 1e300, hi = -1e300;
  for (int v : vertices) lo = std::min(lo, double(x(v, 0))), hi = std::max(hi, double(x(v, 0)));
  return hi - lo;
}

const Field kLinear = [](const Eigen::Vector2d& p) { return 0.3 * p.x() - 0.2 * p.y() + 0.05; };
const Field kQuadratic = [](const Eigen::Vector2d& p) { return 2.0 * p.x() * p.x() + p.x() * p.y() - p.y() * p.y(); };
// One period across the ~0.6 m layout.
const Field kSin = [](const Eigen::Vector2d& p) { return 0.02 * std::sin(10.0 * p.x()) * std::cos(10.0 * p.y()); };

bool inside(const pp::RasterOperator& r, size_t i) { return r.mask[i] == uint8_t(pp::PixelClass::Inside); }
bool padding(const pp::RasterOperator& r, size_t i) { return r.mask[i] == uint8_t(pp::PixelClass::Padding); }

/// Vertices whose 4 bilinear taps are all inside pixels.
std::vector<bool> tapsInside(const pp::RasterOperator& raster, const pp::SampleOperator& sample) {
  std::vector<bool> result(sample.matrix.rows(), false);
  for (int v : sample.vertices) {
    bool all = sample.matrix.row(v).nonZeros() > 0;
    for (pp::SparseOperator::InnerIterator it(sample.matrix, v); it; ++it) all = all && inside(raster, it.col());
    result[v] = all;
  }
  return result;
}

struct RoundTrip {
  double interior = 0;  ///< max |error| / range over vertices whose taps are all inside
  double all = 0;       ///< max |error| / range over every vertex of the layout
};

RoundTrip roundTrip(int size, const Field& field) {
  RoundTrip worst;
  for (int layout = 0; layout < 2; ++layout) {
    pp::RasterOperator raster = pp::buildRaster(shirt(), layout, pp::layoutFrame(shirt(), layout, size));
    pp::SampleOperator sample = pp::buildSample(shirt(), raster);
    Eigen::MatrixXf x = vertexField(shirt(), layout, field);
    Eigen::MatrixXf back = sample.apply(raster.apply(x));
    std::vector<bool> interior = tapsInside(raster, sample);
    double range = rangeOf(x, raster.vertices);
    for (int v : raster.vertices) {
      double e = (back.row(v) - x.row(v)).cwiseAbs().maxCoeff() / (2 * range);  // column 1 is 2 * field
      worst.all = std::max(worst.all, e);
      if (interior[v]) worst.interior = std::max(worst.interior, e);
    }
  }
  return worst;
}

}  // namespace

TEST(Raster, ConstantFieldIsConstantOnInsideAndPaddingPixels) {
  pp::RasterOperator raster = pp::buildRaster(shirt(), 0, pp::layoutFrame(shirt(), 0, 256));
  Eigen::MatrixXf x = Eigen::MatrixXf::Constant(shirt().mesh.numVertices(), 3, 0.25f);
  Eigen::MatrixXf image = raster.apply(x);
  for (size_t i = 0; i < raster.mask.size(); ++i) {
    float expected = raster.mask[i] == 0 ? 0.0f : 0.25f;
    ASSERT_NEAR(image(i, 0), expected, 1e-6) << "pixel " << i << " class " << int(raster.mask[i]);
  }
}

TEST(Raster, LinearFieldIsExactInside) {
  for (int layout = 0; layout < 2; ++layout) {
    pp::ImageFrame frame = pp::layoutFrame(shirt(), layout, 512);
    pp::RasterOperator raster = pp::buildRaster(shirt(), layout, frame);
    Eigen::MatrixXf image = raster.apply(vertexField(shirt(), layout, kLinear));
    double worst = 0;
    for (int y = 0; y < frame.height; ++y)
      for (int x = 0; x < frame.width; ++x) {
        size_t i = size_t(y) * frame.width + x;
        if (inside(raster, i)) worst = std::max(worst, std::abs(image(i, 0) - kLinear(frame.pixelCentre(x, y))));
      }
    EXPECT_LT(worst, 1e-6) << "layout " << layout;
  }
}

TEST(Raster, MaskCountsMatchTheLayoutArea) {
  for (int size : {256, 512}) {
    for (int layout = 0; layout < 2; ++layout) {
      pp::ImageFrame frame = pp::layoutFrame(shirt(), layout, size);
      pp::RasterOperator raster = pp::buildRaster(shirt(), layout, frame);
      double area = 0;
      for (int f = 0; f < shirt().mesh.numFaces(); ++f) {
        if (shirt().faceLayout[f] != layout) continue;
        Eigen::Vector2d a = shirt().mesh.UV.row(shirt().mesh.FUV(f, 0)),
                        b = shirt().mesh.UV.row(shirt().mesh.FUV(f, 1)),
                        c = shirt().mesh.UV.row(shirt().mesh.FUV(f, 2));
        area += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      }
      const double pixelArea = frame.metresPerPixel * frame.metresPerPixel;
      const int in = raster.count(pp::PixelClass::Inside), pad = raster.count(pp::PixelClass::Padding);
      EXPECT_NEAR(in * pixelArea, area, 0.02 * area) << size << " layout " << layout;
      // Padding: a band of 16 px around the outline, clipped by the image edge; between 5% and 100% of the inside.
      EXPECT_GT(pad, 0.05 * in);
      EXPECT_LT(pad, 1.0 * in);
      EXPECT_EQ(in + pad + raster.count(pp::PixelClass::Empty), size * size);
      // Every row sums to 1 (partition of unity) except empty rows.
      Eigen::VectorXf sums = raster.matrix * Eigen::VectorXf::Ones(raster.matrix.cols());
      for (size_t i = 0; i < raster.mask.size(); ++i) ASSERT_NEAR(sums[i], raster.mask[i] ? 1.0f : 0.0f, 1e-5);
    }
  }
}

TEST(Raster, PaddingIsWithinItsWidthAndEmptyBeyond) {
  pp::ImageFrame frame = pp::layoutFrame(shirt(), 0, 256);
  pp::RasterOptions options;
  options.padding = 5;
  pp::RasterOperator raster = pp::buildRaster(shirt(), 0, frame, options);
  // A padding pixel has an inside pixel within 5 px (+1 for pixel centres); an empty pixel has none within 4.
  auto nearestInside = [&](int x, int y, int reach) {
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        int u = x + dx, v = y + dy;
        if (u >= 0 && v >= 0 && u < 256 && v < 256 && dx * dx + dy * dy <= reach * reach &&
            inside(raster, size_t(v) * 256 + u))
          return true;
      }
    return false;
  };
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      size_t i = size_t(y) * 256 + x;
      if (padding(raster, i)) {
        ASSERT_TRUE(nearestInside(x, y, 6)) << x << ", " << y;
      }
      if (raster.mask[i] == 0) {
        ASSERT_FALSE(nearestInside(x, y, 4)) << x << ", " << y;
      }
    }
}

TEST(Raster, PaddingBandIsContinuousWithTheInside) {
  for (const Field* field : {&kLinear, &kSin}) {
    pp::ImageFrame frame = pp::layoutFrame(shirt(), 1, 512);
    pp::RasterOperator raster = pp::buildRaster(shirt(), 1, frame);
    Eigen::MatrixXf image = raster.apply(vertexField(shirt(), 1, *field));
    // Largest gradient norm of the field over the layout, per pixel (finite differences between inside neighbours).
    double gradient = 0;
    for (int y = 0; y + 1 < 512; ++y)
      for (int x = 0; x + 1 < 512; ++x) {
        size_t i = size_t(y) * 512 + x;
        if (inside(raster, i) && inside(raster, i + 1) && inside(raster, i + 512))
          gradient =
              std::max(gradient, double(std::hypot(image(i + 1, 0) - image(i, 0), image(i + 512, 0) - image(i, 0))));
      }
    // gradient is per pixel already: the bound is gradient x 2 pixels.
    int pairs = 0;
    for (int y = 0; y + 1 < 512; ++y)
      for (int x = 0; x + 1 < 512; ++x) {
        size_t i = size_t(y) * 512 + x;
        for (size_t j : {i + 1, i + 512}) {
          if (!((inside(raster, i) && padding(raster, j)) || (padding(raster, i) && inside(raster, j)))) continue;
          ++pairs;
          ASSERT_LE(std::abs(image(i, 0) - image(j, 0)), 2 * gradient + 1e-6) << "pixels " << i << ", " << j;
        }
      }
    EXPECT_GT(pairs, 500);
  }
}

TEST(Raster, RoundTripErrorIsSmall) {
  // Errors relative to the field's range over the layout; the figures are quoted in raster.h.
  for (int size : {256, 512}) {
    RoundTrip linear = roundTrip(size, kLinear), quadratic = roundTrip(size, kQuadratic), sine = roundTrip(size, kSin);
    std::cout << "[round trip " << size << "] linear interior " << linear.interior << " all " << linear.all
              << "; quadratic interior " << quadratic.interior << " all " << quadratic.all << "; sin interior "
              << sine.interior << " all " << sine.all << "\n";
    EXPECT_LT(linear.interior, 1e-6);
    const double pixelFraction = 256.0 / size;  // boundary errors scale with the pixel size
    EXPECT_LT(linear.all, 1.6e-3 * pixelFraction);
    EXPECT_LT(quadratic.interior, 1.5e-4 * pixelFraction);
    EXPECT_LT(quadratic.all, 3.5e-3);
    EXPECT_LT(sine.interior, 2.5e-3 * pixelFraction);
    EXPECT_LT(sine.all, 5e-3 * pixelFraction);
  }
}

TEST(Raster, SampleRowsArePartitionsOfUnity) {
  pp::RasterOperator raster = pp::buildRaster(shirt(), 0, pp::layoutFrame(shirt(), 0, 256));
  pp::SampleOperator sample = pp::buildSample(shirt(), raster);
  Eigen::VectorXf sums = sample.matrix * Eigen::VectorXf::Ones(sample.matrix.cols());
  std::vector<bool> inLayout(shirt().mesh.numVertices(), false);
  for (int v : sample.vertices) inLayout[v] = true;
  for (int v = 0; v < shirt().mesh.numVertices(); ++v) ASSERT_NEAR(sums[v], inLayout[v] ? 1.0f : 0.0f, 1e-5) << v;
}

TEST(Raster, OperatorsSurviveSaveAndLoad) {
  auto dir = freshDir("ops");
  pp::RasterOperator raster = pp::buildRaster(shirt(), 1, pp::layoutFrame(shirt(), 1, 256));
  pp::SampleOperator sample = pp::buildSample(shirt(), raster);
  pp::saveOperator(dir / "r.op", raster);
  pp::saveOperator(dir / "s.op", sample);
  pp::RasterOperator r2 = pp::loadRasterOperator(dir / "r.op");
  pp::SampleOperator s2 = pp::loadSampleOperator(dir / "s.op");
  EXPECT_EQ(r2.mask, raster.mask);
  EXPECT_EQ(r2.vertices, raster.vertices);
  EXPECT_EQ(r2.layout, 1);
  EXPECT_EQ(r2.frame.topLeft, raster.frame.topLeft);
  EXPECT_EQ(r2.frame.metresPerPixel, raster.frame.metresPerPixel);
  EXPECT_EQ((Eigen::MatrixXf(r2.matrix) - Eigen::MatrixXf(raster.matrix)).cwiseAbs().maxCoeff(), 0.0f);
  Eigen::MatrixXf x = vertexField(shirt(), 1, kSin);
  EXPECT_EQ((s2.apply(r2.apply(x)) - sample.apply(raster.apply(x))).cwiseAbs().maxCoeff(), 0.0f);
  // The wrong kind, a flipped byte and a truncated file are refused, naming the file.
  EXPECT_NE(inputErrorOf([&] { pp::loadSampleOperator(dir / "r.op"); }).find("r.op"), std::string::npos);
  std::string bytes;
  {
    std::ifstream in(dir / "r.op", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  std::ofstream(dir / "flipped.op", std::ios::binary) << flipped;
  std::ofstream(dir / "short.op", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  std::ofstream(dir / "junk.op", std::ios::binary) << "not an operator";
  for (const char* name : {"flipped.op", "short.op", "junk.op", "missing.op"}) {
    std::string message = inputErrorOf([&] { pp::loadRasterOperator(dir / name); });
    EXPECT_NE(message.find(name), std::string::npos) << message;
  }
}

// Found by fuzzing: a row index that rises past the entries in row 1 and falls back later sent row 0's loop over the
// entries past their arrays before the fall was seen. The whole index is checked first now.
TEST(Raster, ARowIndexPastTheEntriesIsRefusedBeforeTheEntriesAreRead) {
  auto dir = freshDir("rowindex");
  pp::RasterOperator raster = pp::buildRaster(shirt(), 1, pp::layoutFrame(shirt(), 1, 64));
  pp::saveOperator(dir / "s.op", pp::buildSample(shirt(), raster));
  std::string bytes;
  {
    std::ifstream in(dir / "s.op", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t outer = 8 + 4 + 3 * 4 + 3 * 8 + 5 * 8;  // magic, kind, layout and size, frame, counts
  const std::int32_t far = 1 << 30;
  std::memcpy(&bytes[outer + 4], &far, 4);  // row 0 would end a billion entries in
  std::uint64_t h = 1469598103934665603ull;  // the file's checksum (FNV-1a with raster.cpp's basis)
  for (size_t i = 0; i + 8 < bytes.size(); ++i) {
    h ^= static_cast<unsigned char>(bytes[i]);
    h *= 1099511628211ull;
  }
  std::memcpy(&bytes[bytes.size() - 8], &h, 8);
  std::ofstream(dir / "bad.op", std::ios::binary) << bytes;
  const std::string message = inputErrorOf([&] { pp::loadSampleOperator(dir / "bad.op"); });
  EXPECT_EQ(message, (dir / "bad.op").string() + ": corrupted row index at row 1") << message;
}

TEST(Raster, BadInputsAreRefused) {
  pp::ImageFrame frame = pp::layoutFrame(shirt(), 0, 64);
  EXPECT_NE(inputErrorOf([&] { pp::buildRaster(shirt(), 5, frame); }).find("layout 5"), std::string::npos);
  pp::RasterOptions bad;
  bad.padding = -1;
  EXPECT_NE(inputErrorOf([&] { pp::buildRaster(shirt(), 0, frame, bad); }).find("padding"), std::string::npos);
  pp::RasterOperator raster = pp::buildRaster(shirt(), 0, frame);
  EXPECT_NE(inputErrorOf([&] { raster.apply(Eigen::MatrixXf::Zero(10, 3)); }).find("10 rows"), std::string::npos);
}

TEST(Raster, FastApplyMatchesTheSparseProduct) {
  pp::RasterOperator raster = pp::buildRaster(shirt(), 1, pp::layoutFrame(shirt(), 1, 128));
  ASSERT_FALSE(raster.packed.rows.empty());
  Eigen::MatrixXf x = Eigen::MatrixXf::Random(shirt().mesh.numVertices(), 3);
  Eigen::MatrixXf reference = raster.matrix * x;
  Eigen::MatrixXf out = Eigen::MatrixXf::Constant(128 * 128, 3, 7.0f);  // stale contents are overwritten
  raster.applyTo(x, out);
  EXPECT_LT((out - reference).cwiseAbs().maxCoeff(), 1e-6);
  // Other column counts and an unpacked operator take the generic path.
  EXPECT_LT((raster.apply(x.leftCols(2)) - reference.leftCols(2)).cwiseAbs().maxCoeff(), 1e-6);
  raster.packed = {};
  EXPECT_LT((raster.apply(x) - reference).cwiseAbs().maxCoeff(), 1e-6);
}
