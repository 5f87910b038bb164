#include "pixelcloth/patches/raster.h"

#include <Eigen/StdVector>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"

namespace pixelcloth::patches {

void RasterOptions::validate() const {
  PIXELCLOTH_CHECK(padding >= 0 && padding <= 4096, "raster padding must be in [0, 4096] pixels, got " << padding);
}

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

void checkFrame(const ImageFrame& frame) {
  PIXELCLOTH_CHECK(frame.width > 0 && frame.height > 0 && frame.width <= 65536 && frame.height <= 65536 &&
                       static_cast<std::int64_t>(frame.width) * frame.height < (std::int64_t{1} << 31),
                   "image frame must be 1 to 65536 pixels wide and high, got " << frame.width << " x " << frame.height);
  PIXELCLOTH_CHECK(std::isfinite(frame.metresPerPixel) && frame.metresPerPixel > 0,
                   "image frame: metres per pixel must be positive, got " << frame.metresPerPixel);
}

/// Up to 3 (vertex, weight) pairs of one pixel.
struct PixelWeights {
  std::array<int, 3> vertex{-1, -1, -1};
  std::array<float, 3> weight{0, 0, 0};
};

SparseOperator assemble(int rows, int cols, const std::vector<PixelWeights>& pixels) {
  SparseOperator m(rows, cols);
  std::vector<int> outer(rows + 1, 0), inner;
  std::vector<float> values;
  inner.reserve(3 * pixels.size());
  values.reserve(3 * pixels.size());
  for (int r = 0; r < rows; ++r) {
    const PixelWeights& p = pixels[r];
    // Sorted columns, duplicates merged, zeros dropped.
    std::array<std::pair<int, float>, 3> entries;
    int n = 0;
    for (int k = 0; k < 3; ++k)
      if (p.vertex[k] >= 0 && p.weight[k] != 0.0f) entries[n++] = {p.vertex[k], p.weight[k]};
    std::sort(entries.begin(), entries.begin() + n);
    for (int k = 0; k < n; ++k) {
      if (!inner.empty() && static_cast<int>(inner.size()) > outer[r] && inner.back() == entries[k].first) {
        values.back() += entries[k].second;
      } else {
        inner.push_back(entries[k].first);
        values.push_back(entries[k].second);
      }
    }
    outer[r + 1] = static_cast<int>(inner.size());
  }
  m.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), m.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), m.innerIndexPtr());
  std::copy(values.begin(), values.end(), m.valuePtr());
  m.finalize();
  return m;
}

}  // namespace

RasterOperator buildRaster(const garment::Garment& garment, int layout, const ImageFrame& frame,
                           const RasterOptions& options) {
  PIXELCLOTH_CHECK(layout >= 0 && layout < garment.numLayouts(),
                   garment.name << ": layout " << layout << " does not exist (" << garment.numLayouts() << " layouts)");
  std::vector<int> faces;
  for (int f = 0; f < garment.mesh.numFaces(); ++f)
    if (garment.faceLayout[f] == layout) faces.push_back(f);
  return buildRaster(garment, layout, faces, frame, options);
}

RasterOperator buildRaster(const garment::Garment& garment, int layout, const std::vector<int>& faces,
                           const ImageFrame& frame, const RasterOptions& options) {
  options.validate();
  checkFrame(frame);
  const core::Mesh& mesh = garment.mesh;
  PIXELCLOTH_CHECK(layout >= 0 && layout < garment.numLayouts(),
                   garment.name << ": layout " << layout << " does not exist (" << garment.numLayouts() << " layouts)");
  PIXELCLOTH_CHECK(mesh.hasUV(), garment.name << ": the garment mesh has no per-corner UVs");
  const int W = frame.width, H = frame.height;
  RasterOperator raster;
  raster.frame = frame;
  raster.layout = layout;
  raster.mask.assign(static_cast<size_t>(W) * H, static_cast<std::uint8_t>(PixelClass::Empty));
  std::vector<PixelWeights> pixels(static_cast<size_t>(W) * H);
  std::set<int> vertexSet;
  auto pixelOf = [&](int uvRow) { return frame.toPixel(mesh.UV.row(uvRow).transpose()); };

  // Inside pixels: scan each triangle's bounding box, barycentric weights at pixel centres.
  for (int f : faces) {
    PIXELCLOTH_CHECK(f >= 0 && f < mesh.numFaces() && garment.faceLayout[f] == layout,
                     garment.name << ": face " << f << " is not a face of layout " << garment.layouts[layout]);
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = pixelOf(mesh.FUV(f, k));
      vertexSet.insert(mesh.F(f, k));
    }
    double area = cross(p[1] - p[0], p[2] - p[0]);
    if (area == 0) continue;
    double lo[2], hi[2];
    for (int d = 0; d < 2; ++d) {
      lo[d] = std::min({p[0][d], p[1][d], p[2][d]});
      hi[d] = std::max({p[0][d], p[1][d], p[2][d]});
    }
    int x0 = std::max(0, static_cast<int>(std::ceil(lo[0] - 0.5))), x1 = std::min(W - 1, (int)std::floor(hi[0] - 0.5));
    int y0 = std::max(0, static_cast<int>(std::ceil(lo[1] - 0.5))), y1 = std::min(H - 1, (int)std::floor(hi[1] - 0.5));
    const double tolerance = -1e-9;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        size_t index = static_cast<size_t>(y) * W + x;
        if (raster.mask[index] == static_cast<std::uint8_t>(PixelClass::Inside)) continue;
        Eigen::Vector2d c(x + 0.5, y + 0.5);
        double b0 = cross(p[1] - c, p[2] - c) / area, b1 = cross(p[2] - c, p[0] - c) / area;
        double b2 = 1.0 - b0 - b1;
        if (b0 < tolerance || b1 < tolerance || b2 < tolerance) continue;
        PixelWeights& w = pixels[index];
        w.vertex = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
        w.weight = {static_cast<float>(b0), static_cast<float>(b1), static_cast<float>(b2)};
        raster.mask[index] = static_cast<std::uint8_t>(PixelClass::Inside);
      }
  }

  // Padding: boundary edges of the face set (UV edges used by one of its faces); each pixel outside within the padding
  // takes the closest point on the closest boundary edge.
  if (options.padding > 0) {
    std::map<std::pair<int, int>, std::array<int, 3>> edges;  // sorted UV pair -> (count, vertex of first, of second)
    for (int f : faces)
      for (int k = 0; k < 3; ++k) {
        int a = mesh.FUV(f, k), b = mesh.FUV(f, (k + 1) % 3);
        int va = mesh.F(f, k), vb = mesh.F(f, (k + 1) % 3);
        if (a > b) {
          std::swap(a, b);
          std::swap(va, vb);
        }
        auto [it, fresh] = edges.try_emplace({a, b}, std::array<int, 3>{0, va, vb});
        ++it->second[0];
      }
    const double pad = options.padding, pad2 = pad * pad;
    std::vector<float> best(static_cast<size_t>(W) * H, std::numeric_limits<float>::infinity());
    for (const auto& [uv, info] : edges) {
      if (info[0] != 1) continue;
      Eigen::Vector2d a = pixelOf(uv.first), b = pixelOf(uv.second), ab = b - a;
      double len2 = ab.squaredNorm();
      int x0 = std::max(0, (int)std::floor(std::min(a.x(), b.x()) - pad - 0.5));
      int x1 = std::min(W - 1, (int)std::ceil(std::max(a.x(), b.x()) + pad - 0.5));
      int y0 = std::max(0, (int)std::floor(std::min(a.y(), b.y()) - pad - 0.5));
      int y1 = std::min(H - 1, (int)std::ceil(std::max(a.y(), b.y()) + pad - 0.5));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          size_t index = static_cast<size_t>(y) * W + x;
          if (raster.mask[index] == static_cast<std::uint8_t>(PixelClass::Inside)) continue;
          Eigen::Vector2d c(x + 0.5, y + 0.5);
          double t = len2 > 0 ? std::clamp((c - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
          double d2 = (a + t * ab - c).squaredNorm();
          if (d2 > pad2 || d2 >= best[index]) continue;
          best[index] = static_cast<float>(d2);
          PixelWeights& w = pixels[index];
          w.vertex = {info[1], info[2], -1};
          w.weight = {static_cast<float>(1.0 - t), static_cast<float>(t), 0.0f};
          raster.mask[index] = static_cast<std::uint8_t>(PixelClass::Padding);
        }
    }
  }
  raster.matrix = assemble(W * H, mesh.numVertices(), pixels);
  raster.vertices.assign(vertexSet.begin(), vertexSet.end());
  raster.pack();
  return raster;
}

void RasterOperator::applyTo(const Eigen::Ref<const Eigen::MatrixXf>& values, Eigen::MatrixXf& out) const {
  PIXELCLOTH_CHECK(values.rows() == matrix.cols(), "raster operator: values have " << values.rows()
                                                                                   << " rows, expected one per vertex ("
                                                                                   << matrix.cols() << ")");
  const Eigen::Index rows = matrix.rows(), k = values.cols();
  if (out.rows() != rows || out.cols() != k) out.resize(rows, k);
  if (k == 3 && packed.numRows == rows && packed.nonZeros == matrix.nonZeros()) {
    // The common case (du, dv, dn): values packed 4 floats per vertex (one load per entry; 48 KB for 3K vertices, in
    // cache), a fixed 3 entries per non-empty row, zeros written in bulk between runs. About 10x Eigen's generic
    // sparse x dense product here (0.3-0.5 ms against 2-7 ms for 512 x 512, 3K vertices, one core).
    thread_local std::vector<Eigen::Array4f, Eigen::aligned_allocator<Eigen::Array4f>> x;
    x.resize(values.rows());
    for (Eigen::Index j = 0; j < values.rows(); ++j) x[j] << values(j, 0), values(j, 1), values(j, 2), 0.0f;
    float* o[3] = {out.col(0).data(), out.col(1).data(), out.col(2).data()};
    const Packed::Row* row = packed.rows.data();
    Eigen::Index previous = 0;
    auto zero = [&](Eigen::Index from, Eigen::Index to) {
      for (float* column : o) std::fill(column + from, column + to, 0.0f);
    };
    for (const auto& [first, last] : packed.runs) {
      zero(previous, first);
      for (int r = first; r < last; ++r, ++row) {
        Eigen::Array4f sum = row->weight[0] * x[row->vertex[0]] + row->weight[1] * x[row->vertex[1]] +
                             row->weight[2] * x[row->vertex[2]];
        o[0][r] = sum[0];
        o[1][r] = sum[1];
        o[2][r] = sum[2];
      }
      previous = last;
    }
    zero(previous, rows);
    return;
  }
  out.noalias() = matrix * values;
}

void RasterOperator::pack() {
  packed = Packed{};
  matrix.makeCompressed();
  const int* outer = matrix.outerIndexPtr();
  const int* inner = matrix.innerIndexPtr();
  const float* value = matrix.valuePtr();
  for (Eigen::Index r = 0; r < matrix.rows(); ++r) {
    const int n = outer[r + 1] - outer[r];
    if (n == 0) continue;
    if (n > 3) {
      packed = Packed{};
      return;
    }
    Packed::Row row;
    for (int k = 0; k < 3; ++k) {
      // Short rows repeat their first column with weight 0.
      row.vertex[k] = inner[outer[r] + (k < n ? k : 0)];
      row.weight[k] = k < n ? value[outer[r] + k] : 0.0f;
    }
    packed.rows.push_back(row);
    if (!packed.runs.empty() && packed.runs.back().second == r)
      ++packed.runs.back().second;
    else
      packed.runs.emplace_back(static_cast<int>(r), static_cast<int>(r + 1));
  }
  packed.numRows = matrix.rows();
  packed.nonZeros = matrix.nonZeros();
}

Eigen::MatrixXf RasterOperator::apply(const Eigen::Ref<const Eigen::MatrixXf>& values) const {
  Eigen::MatrixXf out;
  applyTo(values, out);
  return out;
}

int RasterOperator::count(PixelClass pixelClass) const {
  return static_cast<int>(std::count(mask.begin(), mask.end(), static_cast<std::uint8_t>(pixelClass)));
}

Eigen::MatrixXf RasterOperator::maskImage() const {
  Eigen::VectorXf pixels(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) pixels[i] = mask[i];
  return toImage(pixels, frame.width, frame.height);
}

SampleOperator buildSample(const garment::Garment& garment, const RasterOperator& raster) {
  const ImageFrame& frame = raster.frame;
  checkFrame(frame);
  const int W = frame.width, H = frame.height;
  PIXELCLOTH_CHECK(raster.mask.size() == static_cast<size_t>(W) * H,
                   "sample operator: the raster mask has " << raster.mask.size() << " pixels, expected " << W * H);
  PIXELCLOTH_CHECK(raster.layout >= 0 && raster.layout < garment.numLayouts(),
                   garment.name << ": layout " << raster.layout << " does not exist");
  const core::Mesh& mesh = garment.mesh;
  std::vector<Eigen::Triplet<float>> triplets;
  triplets.reserve(4 * raster.vertices.size());
  for (int v : raster.vertices) {
    PIXELCLOTH_CHECK(v >= 0 && v < mesh.numVertices() && garment.vertexUV(v, raster.layout) >= 0,
                     garment.name << ": vertex " << v + 1 << " has no UV in layout " << garment.layouts[raster.layout]);
    Eigen::Vector2d p = frame.toPixel(mesh.UV.row(garment.vertexUV(v, raster.layout)).transpose());
    double fx = p.x() - 0.5, fy = p.y() - 0.5;
    int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    double tx = fx - x0, ty = fy - y0;
    std::array<std::pair<int, double>, 4> taps;
    int n = 0;
    double total = 0;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        int x = x0 + dx, y = y0 + dy;
        double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
        if (x < 0 || y < 0 || x >= W || y >= H || w <= 0) continue;
        int index = y * W + x;
        if (raster.mask[index] == static_cast<std::uint8_t>(PixelClass::Empty)) continue;
        taps[n++] = {index, w};
        total += w;
      }
    if (total <= 0) continue;
    for (int k = 0; k < n; ++k) triplets.emplace_back(v, taps[k].first, static_cast<float>(taps[k].second / total));
  }
  SampleOperator sample;
  sample.frame = frame;
  sample.layout = raster.layout;
  sample.vertices = raster.vertices;
  sample.matrix.resize(mesh.numVertices(), static_cast<Eigen::Index>(W) * H);
  sample.matrix.setFromTriplets(triplets.begin(), triplets.end());
  sample.matrix.makeCompressed();
  return sample;
}

Eigen::MatrixXf SampleOperator::apply(const Eigen::Ref<const Eigen::MatrixXf>& image) const {
  PIXELCLOTH_CHECK(image.rows() == matrix.cols(),
                   "sample operator: the image has " << image.rows() << " pixels, expected " << matrix.cols());
  Eigen::MatrixXf out = matrix * image;
  return out;
}

Eigen::MatrixXf toImage(const Eigen::Ref<const Eigen::VectorXf>& pixels, int width, int height) {
  PIXELCLOTH_CHECK(pixels.size() == static_cast<Eigen::Index>(width) * height,
                   "image: " << pixels.size() << " pixels for " << width << " x " << height);
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Eigen::VectorXf copy = pixels;
  return Eigen::Map<const RowMajor>(copy.data(), height, width);
}

Eigen::VectorXf fromImage(const Eigen::MatrixXf& image) {
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor rowMajor = image;
  return Eigen::Map<const Eigen::VectorXf>(rowMajor.data(), rowMajor.size());
}

// ---- Binary operator files -------------------------------------------------------------------------------------
// Layout (little endian): magic "PXCLOP1\n", kind u32 (1 raster, 2 sample), layout i32, width i32, height i32,
// topLeft 2 x f64, metresPerPixel f64, rows i64, cols i64, nnz i64, maskLength i64, vertexCount i64,
// outer (rows + 1) x i32, inner nnz x i32, values nnz x f32, mask maskLength x u8, vertices vertexCount x i32,
// then an FNV-1a 64-bit checksum of every byte before it.

namespace {

constexpr char kMagic[8] = {'P', 'X', 'C', 'L', 'O', 'P', '1', '\n'};
enum : std::uint32_t { kRaster = 1, kSample = 2 };

std::uint64_t fnv1a(const char* data, size_t size) {
  std::uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

struct OperatorFile {
  std::uint32_t kind = 0;
  int layout = 0;
  ImageFrame frame;
  SparseOperator matrix;
  std::vector<std::uint8_t> mask;
  std::vector<int> vertices;
};

template <typename T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <typename T>
void putArray(std::string& out, const T* data, size_t count) {
  out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

void writeOperatorFile(const std::filesystem::path& path, const OperatorFile& file) {
  SparseOperator m = file.matrix;
  m.makeCompressed();
  std::string bytes(kMagic, sizeof(kMagic));
  put(bytes, file.kind);
  put<std::int32_t>(bytes, file.layout);
  put<std::int32_t>(bytes, file.frame.width);
  put<std::int32_t>(bytes, file.frame.height);
  put(bytes, file.frame.topLeft.x());
  put(bytes, file.frame.topLeft.y());
  put(bytes, file.frame.metresPerPixel);
  put<std::int64_t>(bytes, m.rows());
  put<std::int64_t>(bytes, m.cols());
  put<std::int64_t>(bytes, m.nonZeros());
  put<std::int64_t>(bytes, static_cast<std::int64_t>(file.mask.size()));
  put<std::int64_t>(bytes, static_cast<std::int64_t>(file.vertices.size()));
  putArray(bytes, m.outerIndexPtr(), m.rows() + 1);
  putArray(bytes, m.innerIndexPtr(), m.nonZeros());
  putArray(bytes, m.valuePtr(), m.nonZeros());
  putArray(bytes, file.mask.data(), file.mask.size());
  putArray(bytes, file.vertices.data(), file.vertices.size());
  put(bytes, fnv1a(bytes.data(), bytes.size()));
  core::writeAtomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    PIXELCLOTH_CHECK(out.good(), path.string() << ": could not write the operator file");
  });
}

OperatorFile readOperatorFile(const std::filesystem::path& path, std::uint32_t expectedKind) {
  const std::string name = path.string();
  std::string bytes = core::readTextFile(path);
  const size_t headerSize = sizeof(kMagic) + 4 + 3 * 4 + 3 * 8 + 5 * 8;
  PIXELCLOTH_CHECK(bytes.size() >= headerSize + 8 && std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) == 0,
                   name << ": not a pixelcloth operator file (bad magic or too short: " << bytes.size() << " bytes)");
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
  PIXELCLOTH_CHECK(stored == fnv1a(bytes.data(), bytes.size() - 8),
                   name << ": checksum mismatch; the operator file is corrupted or truncated");
  size_t at = sizeof(kMagic);
  auto get = [&](auto& value) {
    PIXELCLOTH_CHECK(at + sizeof(value) <= bytes.size() - 8, name << ": operator file truncated at byte " << at);
    std::memcpy(&value, bytes.data() + at, sizeof(value));
    at += sizeof(value);
  };
  auto getArray = [&](auto* data, std::int64_t count) {
    using T = std::remove_pointer_t<decltype(data)>;
    PIXELCLOTH_CHECK(count >= 0 && static_cast<std::uint64_t>(count) <= (bytes.size() - 8 - at) / sizeof(T),
                     name << ": operator file truncated (" << count << " elements do not fit)");
    // An empty array (the sample operator's mask) has no storage: memcpy's pointers must not be null, even for 0 bytes.
    if (count > 0) std::memcpy(data, bytes.data() + at, count * sizeof(T));
    at += count * sizeof(T);
  };
  OperatorFile file;
  std::int32_t layout, width, height;
  double x, y, mpp;
  std::int64_t rows, cols, nnz, maskLength, vertexCount;
  get(file.kind);
  get(layout), get(width), get(height), get(x), get(y), get(mpp);
  get(rows), get(cols), get(nnz), get(maskLength), get(vertexCount);
  PIXELCLOTH_CHECK(file.kind == expectedKind, name << ": holds a " << (file.kind == kRaster ? "raster" : "sample")
                                                   << " operator, expected a "
                                                   << (expectedKind == kRaster ? "raster" : "sample") << " operator");
  file.layout = layout;
  file.frame.width = width;
  file.frame.height = height;
  file.frame.topLeft = {x, y};
  file.frame.metresPerPixel = mpp;
  std::int64_t pixels = static_cast<std::int64_t>(width) * height;
  bool shapeOk = width > 0 && height > 0 && std::isfinite(mpp) && mpp > 0 && rows >= 0 && cols >= 0 && nnz >= 0 &&
                 rows < (std::int64_t{1} << 31) && (rows + 1) * 4 <= static_cast<std::int64_t>(bytes.size()) &&
                 cols < (std::int64_t{1} << 31) &&
                 (expectedKind == kRaster ? rows == pixels && maskLength == pixels : cols == pixels && maskLength == 0);
  PIXELCLOTH_CHECK(shapeOk, name << ": inconsistent operator header (" << rows << " x " << cols << " for a " << width
                                 << " x " << height << " frame)");
  std::vector<int> outer(rows + 1), inner;
  std::vector<float> values;
  getArray(outer.data(), rows + 1);
  PIXELCLOTH_CHECK(nnz <= static_cast<std::int64_t>(bytes.size()), name << ": operator file truncated");
  inner.resize(nnz);
  values.resize(nnz);
  getArray(inner.data(), nnz);
  getArray(values.data(), nnz);
  file.mask.resize(maskLength);
  getArray(file.mask.data(), maskLength);
  PIXELCLOTH_CHECK(vertexCount >= 0 && vertexCount <= cols + rows, name << ": bad vertex count " << vertexCount);
  file.vertices.resize(vertexCount);
  getArray(file.vertices.data(), vertexCount);
  PIXELCLOTH_CHECK(at == bytes.size() - 8, name << ": " << (bytes.size() - 8 - at) << " unexpected trailing bytes");
  PIXELCLOTH_CHECK(outer[0] == 0 && outer[rows] == nnz, name << ": corrupted row index");
  // The whole row index first: a later row's bad start must not send an earlier row's entries past the arrays.
  for (std::int64_t r = 0; r < rows; ++r) {
    PIXELCLOTH_CHECK(outer[r] <= outer[r + 1], name << ": corrupted row index at row " << r);
  }
  for (std::int64_t r = 0; r < rows; ++r) {
    for (int p = outer[r]; p < outer[r + 1]; ++p)
      PIXELCLOTH_CHECK(
          inner[p] >= 0 && inner[p] < cols && (p == outer[r] || inner[p] > inner[p - 1]) && std::isfinite(values[p]),
          name << ": corrupted entry " << p << " in row " << r);
  }
  for (std::uint8_t m : file.mask) PIXELCLOTH_CHECK(m <= 2, name << ": corrupted mask value " << int(m));
  file.matrix.resize(rows, cols);
  file.matrix.resizeNonZeros(nnz);
  std::copy(outer.begin(), outer.end(), file.matrix.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), file.matrix.innerIndexPtr());
  std::copy(values.begin(), values.end(), file.matrix.valuePtr());
  return file;
}

}  // namespace

void saveOperator(const std::filesystem::path& path, const RasterOperator& raster) {
  writeOperatorFile(path, {kRaster, raster.layout, raster.frame, raster.matrix, raster.mask, raster.vertices});
}

void saveOperator(const std::filesystem::path& path, const SampleOperator& sample) {
  writeOperatorFile(path, {kSample, sample.layout, sample.frame, sample.matrix, {}, sample.vertices});
}

namespace {
/// The fields both operators share, moved out of a file that was read.
template <typename Operator>
Operator operatorFrom(OperatorFile& file) {
  Operator op;
  op.frame = file.frame;
  op.layout = file.layout;
  op.matrix = std::move(file.matrix);
  op.vertices = std::move(file.vertices);
  return op;
}
}  // namespace

RasterOperator loadRasterOperator(const std::filesystem::path& path) {
  OperatorFile file = readOperatorFile(path, kRaster);
  RasterOperator raster = operatorFrom<RasterOperator>(file);
  raster.mask = std::move(file.mask);
  raster.pack();
  return raster;
}

SampleOperator loadSampleOperator(const std::filesystem::path& path) {
  OperatorFile file = readOperatorFile(path, kSample);
  return operatorFrom<SampleOperator>(file);
}

}  // namespace pixelcloth::patches
