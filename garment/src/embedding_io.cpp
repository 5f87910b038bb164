// Embedding arrays on disk: embedding_triangle.npy, embedding_barycentric.npy, embedding_tangent.npy.
#include <limits>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/garment/embedding.h"

namespace pixelcloth::garment {

using namespace core;

namespace fs = std::filesystem;

void saveEmbedding(const fs::path& folder, const Embedding& embedding) {
  embedding.validate(std::numeric_limits<int>::max(), "saveEmbedding");
  std::vector<std::int32_t> triangles(embedding.triangle.data(), embedding.triangle.data() + embedding.size());
  writeNpy(folder / "embedding_triangle.npy", triangles, {embedding.size()});
  writeNpy(folder / "embedding_barycentric.npy", Eigen::MatrixXd(embedding.barycentric));
  writeNpy(folder / "embedding_tangent.npy", Eigen::MatrixXd(embedding.tangentCoords));
}

Embedding loadEmbedding(const fs::path& folder, int numBodyFaces) {
  const fs::path trianglePath = folder / "embedding_triangle.npy";
  // The header is checked before the data is read.
  const NpyHeader header = readNpyHeader(trianglePath);
  PIXELCLOTH_CHECK(header.shape.size() == 1, trianglePath.string()
                                                 << ": shape " << header.shapeString() << ", expected (#C,)");
  PIXELCLOTH_CHECK(header.dtype == "<i4",
                   trianglePath.string() << ": dtype " << header.dtype << ", expected <i4 (body triangle indices)");
  const NpyArray triangles = readNpy(trianglePath);
  const std::int32_t* values = triangles.data<std::int32_t>();
  const std::int64_t n = triangles.shape[0];
  Embedding embedding;
  embedding.triangle = Eigen::Map<const Eigen::VectorXi>(values, n);
  embedding.barycentric = readNpyMatrixD(folder / "embedding_barycentric.npy", n, 3);
  embedding.tangentCoords = readNpyMatrixD(folder / "embedding_tangent.npy", n, 2);
  embedding.validate(numBodyFaces < 0 ? std::numeric_limits<int>::max() : numBodyFaces, folder.string() + "/embedding");
  return embedding;
}

}  // namespace pixelcloth::garment
