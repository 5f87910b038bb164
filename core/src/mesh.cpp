#include "pixelcloth/core/mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "pixelcloth/core/error.h"

namespace pixelcloth::core {

void Mesh::validate(const std::string& context) const {
  PIXELCLOTH_CHECK(V.rows() > 0, context << ": the mesh has no vertices");
  PIXELCLOTH_CHECK(F.rows() > 0, context << ": the mesh has no faces");
  for (int i = 0; i < V.rows(); ++i) {
    PIXELCLOTH_CHECK(V.row(i).allFinite(), context << ": vertex " << i + 1 << " has a non-finite coordinate (" << V(i, 0)
                                                   << ", " << V(i, 1) << ", " << V(i, 2) << ")");
    PIXELCLOTH_CHECK(V.row(i).cwiseAbs().maxCoeff() <= kMaxCoordinate,
                     context << ": vertex " << i + 1 << " has a coordinate beyond " << kMaxCoordinate << " in size ("
                             << V(i, 0) << ", " << V(i, 1) << ", " << V(i, 2) << ")");
  }
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      PIXELCLOTH_CHECK(F(f, k) >= 0 && F(f, k) < V.rows(), context << ": face " << f + 1 << " uses vertex " << F(f, k) + 1
                                                                   << ", but the mesh has " << V.rows() << " vertices");
    }
    PIXELCLOTH_CHECK(
        F(f, 0) != F(f, 1) && F(f, 1) != F(f, 2) && F(f, 0) != F(f, 2),
        context << ": face " << f + 1 << " repeats a vertex (" << F(f, 0) + 1 << ", " << F(f, 1) + 1 << ", " << F(f, 2) + 1
                << ")");
  }
  if (FUV.rows() > 0) {
    PIXELCLOTH_CHECK(FUV.rows() == F.rows(), context << ": " << FUV.rows() << " texture faces for " << F.rows()
                                                     << " faces; expected one per face");
    for (int f = 0; f < FUV.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        PIXELCLOTH_CHECK(FUV(f, k) >= 0 && FUV(f, k) < UV.rows(), context << ": face " << f
                                                                          << " uses texture coordinate " << FUV(f, k)
                                                                          << ", but there are " << UV.rows());
      }
    }
    for (int i = 0; i < UV.rows(); ++i) {
      PIXELCLOTH_CHECK(UV.row(i).allFinite(), context << ": texture coordinate " << i << " is not finite");
    }
  }
  for (const auto& [name, values] : vertexAttributes) {
    PIXELCLOTH_CHECK(values.rows() == V.rows(), context << ": vertex attribute '" << name << "' has " << values.rows()
                                                        << " rows, expected " << V.rows());
  }
  for (const auto& [name, values] : faceAttributes) {
    PIXELCLOTH_CHECK(values.rows() == F.rows(), context << ": face attribute '" << name << "' has " << values.rows()
                                                        << " rows, expected " << F.rows());
  }
}

Eigen::Vector3d barycentricCoordinates(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), dp1 = d.dot(e1), dp2 = d.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double v = det > 0 ? (d22 * dp1 - d12 * dp2) / det : 0.0;
  const double w = det > 0 ? (d11 * dp2 - d12 * dp1) / det : 0.0;
  const Eigen::Vector3d bary = Eigen::Vector3d(1.0 - v - w, v, w).cwiseMax(0.0);
  return bary / bary.sum();
}

Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: test the corner regions, then the edge regions, else the interior.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {1 - t, t, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {1 - t, 0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - t, t};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) return {1, 0, 0};  // degenerate triangle: every region test above was inconclusive
  return {va / sum, vb / sum, vc / sum};
}

Eigen::MatrixX3d faceNormals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d N(F.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    Eigen::Vector3d n = (b - a).cross(c - a);
    double len = n.norm();
    N.row(f) = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
  }
  return N;
}

Eigen::MatrixX3d vertexNormals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    Eigen::Vector3d n = (b - a).cross(c - a);  // length = twice the area: area weighting
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();
  }
  for (int i = 0; i < N.rows(); ++i) {
    double len = N.row(i).norm();
    if (len > 0) N.row(i) /= len;
  }
  return N;
}

TopologyReport checkTopology(int numVertices, const Eigen::MatrixX3i& F) {
  TopologyReport report;
  int problemVertex = -1;
  auto note = [&](const std::string& problem, int vertex) {
    if (!report.firstProblem.empty()) return;
    report.firstProblem = problem;
    problemVertex = vertex;
  };
  // Directed half-edges keyed by (from, to).
  std::unordered_map<std::uint64_t, int> directed;
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); };
  directed.reserve(F.rows() * 3);
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) ++directed[key(F(f, k), F(f, (k + 1) % 3))];
  }
  for (const auto& [k, count] : directed) {
    int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffffu);
    auto reverse = directed.find(key(b, a));
    int back = reverse == directed.end() ? 0 : reverse->second;
    if (count > 1) {
      ++report.inconsistentEdges;
      note("edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) + ") is used " + std::to_string(count) +
               " times in the same direction",
           a);
    }
    if (a < b || back == 0) {
      int uses = count + back;
      if (uses == 1) {
        ++report.boundaryEdges;
        note("edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) + ") is on a boundary (used by one face)",
             a);
      } else if (uses > 2) {
        ++report.nonManifoldEdges;
        note("edge (" + std::to_string(std::min(a, b) + 1) + ", " + std::to_string(std::max(a, b) + 1) +
                 ") is shared by " + std::to_string(uses) + " faces",
             a);
      }
    }
  }
  // Vertex fans: the faces around a vertex must be connected through shared edges.
  std::vector<std::vector<int>> vertexFaces(numVertices);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) vertexFaces[F(f, k)].push_back(f);
  for (int v = 0; v < numVertices; ++v) {
    const auto& faces = vertexFaces[v];
    if (faces.empty()) {
      ++report.isolatedVertices;
      continue;
    }
    // Union faces of the fan that share an edge through v.
    std::vector<int> parent(faces.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
    std::unordered_map<int, int> firstFaceOfNeighbour;
    for (size_t i = 0; i < faces.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        int w = F(faces[i], k);
        if (w == v) continue;
        auto [it, inserted] = firstFaceOfNeighbour.emplace(w, static_cast<int>(i));
        if (!inserted) parent[find(static_cast<int>(i))] = find(it->second);
      }
    }
    int roots = 0;
    for (size_t i = 0; i < faces.size(); ++i) roots += find(static_cast<int>(i)) == static_cast<int>(i);
    if (roots > 1) {
      ++report.nonManifoldVertices;
      note("vertex " + std::to_string(v + 1) + " joins " + std::to_string(roots) + " separate fans of faces", v);
    }
  }
  const std::vector<int> component = faceComponents(numVertices, F);
  for (int c : component) {
    if (c >= static_cast<int>(report.componentFaces.size())) report.componentFaces.resize(c + 1, 0);
    ++report.componentFaces[c];
  }
  report.components = static_cast<int>(report.componentFaces.size());
  if (problemVertex >= 0 && !vertexFaces[problemVertex].empty())
    report.firstProblemComponent = component[vertexFaces[problemVertex].front()] + 1;
  return report;
}

std::vector<int> faceComponents(int numVertices, const Eigen::MatrixX3i& F) {
  // Faces joined through shared vertices (union-find), then the components ranked by size.
  std::vector<int> parent(F.rows());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
  std::vector<int> firstFace(numVertices, -1);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      int& first = firstFace[F(f, k)];
      if (first < 0)
        first = f;
      else
        parent[find(f)] = find(first);
    }
  std::unordered_map<int, int> size;
  for (int f = 0; f < F.rows(); ++f) ++size[find(f)];
  std::vector<std::pair<int, int>> roots(size.begin(), size.end());  // (root, faces)
  std::sort(roots.begin(), roots.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  std::unordered_map<int, int> rank;
  for (size_t r = 0; r < roots.size(); ++r) rank[roots[r].first] = static_cast<int>(r);
  std::vector<int> component(F.rows());
  for (int f = 0; f < F.rows(); ++f) component[f] = rank[find(f)];
  return component;
}

Mesh largestComponent(const Mesh& mesh) {
  const std::vector<int> component = faceComponents(mesh.numVertices(), mesh.F);
  std::vector<int> kept;
  for (int f = 0; f < mesh.numFaces(); ++f)
    if (component[f] == 0) kept.push_back(f);
  std::vector<int> index(mesh.numVertices(), -1);
  for (int f : kept)
    for (int k = 0; k < 3; ++k) index[mesh.F(f, k)] = 0;
  int next = 0;
  for (int& i : index)
    if (i == 0) i = next++;
  Mesh result;
  result.V.resize(next, 3);
  for (auto& [name, values] : mesh.vertexAttributes) result.vertexAttributes[name].resize(next, values.cols());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    if (index[v] < 0) continue;
    result.V.row(index[v]) = mesh.V.row(v);
    for (auto& [name, values] : mesh.vertexAttributes) result.vertexAttributes[name].row(index[v]) = values.row(v);
  }
  const auto faces = static_cast<Eigen::Index>(kept.size());
  result.F.resize(faces, 3);
  for (Eigen::Index i = 0; i < faces; ++i)
    for (int k = 0; k < 3; ++k) result.F(i, k) = index[mesh.F(kept[i], k)];
  if (mesh.hasUV()) {  // the texture coordinates stay; the kept faces keep their corners' indices into them
    result.UV = mesh.UV;
    result.FUV.resize(faces, 3);
    for (Eigen::Index i = 0; i < faces; ++i) result.FUV.row(i) = mesh.FUV.row(kept[i]);
  }
  for (auto& [name, values] : mesh.faceAttributes) {
    Eigen::VectorXi& out = result.faceAttributes[name];
    out.resize(faces);
    for (Eigen::Index i = 0; i < faces; ++i) out(i) = values(kept[i]);
  }
  return result;
}

double enclosedVolume(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  double volume = 0;
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

}  // namespace pixelcloth::core
