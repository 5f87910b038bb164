#include "pixelcloth/core/mesh_io.h"

// OpenMesh's VectorT default constructor leaves its values uninitialised on purpose (property arrays grow with
// push_back(T())); GCC warns about that inside OpenMesh's templates, not about this file.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"

namespace pixelcloth::core {

namespace fs = std::filesystem;

namespace {

// Double points so that nothing is lost inside our code; OpenMesh's readers and writers still go through float.
struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

// Enough digits for a float to survive text exactly (OpenMesh's default of 6 does not).
constexpr std::streamsize kFloatDigits = 9;

void silenceOpenMesh() {
  static std::once_flag once;
  std::call_once(once, [] {
    omerr().disable();
    omlog().disable();
    omout().disable();
  });
}

enum class Format { Obj, Ply, Off };

Format formatOf(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj") return Format::Obj;
  if (ext == ".ply") return Format::Ply;
  if (ext == ".off") return Format::Off;
  PIXELCLOTH_FAIL(path.string() << ": unsupported mesh format '" << (ext.empty() ? "(no extension)" : ext)
                                << "'; expected one of .obj, .ply, .off");
}

const char* extensionOf(Format format) {
  switch (format) {
    case Format::Obj:
      return "obj";
    case Format::Ply:
      return "ply";
    case Format::Off:
      return "off";
  }
  return "";
}

std::string nonManifoldMessage(const fs::path& path, long long failedFaces) {
  std::ostringstream s;
  s << path.string() << ": " << std::max(1LL, failedFaces)
    << " faces could not be added without duplicating vertices: the mesh is not manifold (e.g. an edge shared by "
       "more than two faces) or not consistently oriented";
  return s.str();
}

// Faces OpenMesh's importer re-added on duplicated vertices: it flags them when the mesh has face status.
long long countFlaggedFaces(const OmMesh& om) {
  long long flagged = 0;
  for (auto f : om.faces()) flagged += om.status(f).fixed_nonmanifold();
  return flagged;
}

// ---------------------------------------------------------------------------------------------------------------
// OBJ pre-scan: OpenMesh's OBJ reader skips or mangles bad input without saying where, so the text is checked here
// first. It also keeps the `vt` table and per-corner `vt` indices: OpenMesh 9 only sets halfedge texture
// coordinates for the last triangle of a fan-triangulated polygon (and at the wrong corners), so per-corner UVs of
// polygons cannot be taken from it.

struct ObjFace {
  std::vector<int> v;   // 0-based vertex indices
  std::vector<int> vt;  // 0-based texture coordinate indices, empty when the face has none
  int line = 0;
};

struct ObjScan {
  int numVertices = 0;
  int numNormals = 0;
  std::vector<Eigen::Vector2d> texcoords;
  std::vector<ObjFace> faces;
};

bool parseNumber(const std::string& token, double& value) {
  const char* begin = token.c_str();
  char* end = nullptr;
  value = std::strtod(begin, &end);
  return end != begin && *end == '\0';
}

bool parseIndex(const std::string& token, long& value) {
  const char* begin = token.c_str();
  char* end = nullptr;
  value = std::strtol(begin, &end, 10);
  return end != begin && *end == '\0';
}

ObjScan scanObj(const fs::path& path, const std::string& text) {
  const std::string file = path.string();
  PIXELCLOTH_CHECK(std::memchr(text.data(), '\0', text.size()) == nullptr,
                   file << ": not a text OBJ file (it contains binary data)");
  ObjScan scan;
  std::vector<std::pair<int, int>> normalUses;  // (face, normal index), range-checked once all normals are known
  int line = 0;
  size_t pos = 0;
  std::vector<std::string> tokens;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::istringstream lineStream(text.substr(pos, end - pos));
    pos = end + 1;
    ++line;
    tokens.clear();
    for (std::string token; lineStream >> token;) tokens.push_back(token);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    const std::string& keyword = tokens[0];
    if (keyword == "v" || keyword == "vt" || keyword == "vn") {
      const bool isVertex = keyword == "v", isTexcoord = keyword == "vt";
      const char* what = isVertex ? "vertex" : isTexcoord ? "texture coordinate" : "normal";
      const int number = isVertex     ? ++scan.numVertices
                         : isTexcoord ? static_cast<int>(scan.texcoords.size()) + 1
                                      : ++scan.numNormals;
      const size_t needed = isTexcoord ? 2 : 3;
      PIXELCLOTH_CHECK(tokens.size() - 1 >= needed, file << ": " << what << " " << number << " has "
                                                         << tokens.size() - 1 << " numbers, expected " << needed
                                                         << " (line " << line << ")");
      double values[3] = {0, 0, 0};
      for (size_t i = 1; i < tokens.size(); ++i) {
        double value = 0;
        PIXELCLOTH_CHECK(parseNumber(tokens[i], value), file << ": " << what << " " << number << " has '" << tokens[i]
                                                             << "' where a number was expected (line " << line << ")");
        PIXELCLOTH_CHECK(std::isfinite(value),
                         file << ": " << what << " " << number << " has a non-finite coordinate (line " << line << ")");
        if (i <= 3) values[i - 1] = value;
      }
      if (isTexcoord) scan.texcoords.emplace_back(values[0], values[1]);
      continue;
    }
    if (keyword != "f") continue;  // groups, objects, materials, smoothing, lines, ... carry no geometry we keep
    ObjFace face;
    face.line = line;
    const int faceNumber = static_cast<int>(scan.faces.size()) + 1;
    PIXELCLOTH_CHECK(tokens.size() - 1 >= 3, file << ": face " << faceNumber << " has " << tokens.size() - 1
                                                  << " corners, expected at least 3 (line " << line << ")");
    // Resolves a 1-based (or negative, relative) index; positive ones are range-checked once the counts are known.
    auto resolve = [&](const std::string& token, const char* what, int definedSoFar) {
      long raw = 0;
      PIXELCLOTH_CHECK(parseIndex(token, raw), file << ": face " << faceNumber << " has '" << token << "' where a "
                                                    << what << " index was expected (line " << line << ")");
      PIXELCLOTH_CHECK(raw != 0, file << ": face " << faceNumber << " uses " << what
                                      << " 0, but OBJ indices start at 1 (line " << line << ")");
      if (raw > 0) {
        PIXELCLOTH_CHECK(raw <= (1L << 30), file << ": face " << faceNumber << " uses " << what << " " << raw
                                                 << ", which is too large (line " << line << ")");
        return static_cast<int>(raw - 1);
      }
      PIXELCLOTH_CHECK(-raw <= definedSoFar, file << ": face " << faceNumber << " uses " << what << " " << raw
                                                  << ", but only " << definedSoFar << " precede it (line " << line
                                                  << ")");
      return static_cast<int>(definedSoFar + raw);
    };
    for (size_t c = 1; c < tokens.size(); ++c) {
      std::vector<std::string> parts;
      std::stringstream cornerStream(tokens[c]);
      for (std::string part; std::getline(cornerStream, part, '/');) parts.push_back(part);
      if (!tokens[c].empty() && tokens[c].back() == '/') parts.push_back("");
      PIXELCLOTH_CHECK(!parts.empty() && parts.size() <= 3 && !parts[0].empty(),
                       file << ": face " << faceNumber << " has a malformed corner '" << tokens[c]
                            << "', expected v, v/vt, v//vn or v/vt/vn (line " << line << ")");
      face.v.push_back(resolve(parts[0], "vertex", scan.numVertices));
      const bool hasTexcoord = parts.size() >= 2 && !parts[1].empty();
      PIXELCLOTH_CHECK(c == 1 || hasTexcoord == !face.vt.empty(),
                       file << ": face " << faceNumber
                            << " gives texture coordinates for some corners only; expected all or none (line " << line
                            << ")");
      if (hasTexcoord) {
        face.vt.push_back(resolve(parts[1], "texture coordinate", static_cast<int>(scan.texcoords.size())));
      }
      if (parts.size() == 3 && !parts[2].empty()) {
        int normal = resolve(parts[2], "normal", scan.numNormals);
        normalUses.emplace_back(static_cast<int>(scan.faces.size()), normal);
      }
    }
    for (size_t i = 0; i < face.v.size(); ++i) {
      for (size_t j = i + 1; j < face.v.size(); ++j) {
        PIXELCLOTH_CHECK(face.v[i] != face.v[j], file << ": face " << faceNumber << " repeats vertex " << face.v[i] + 1
                                                      << " (line " << line << ")");
      }
    }
    scan.faces.push_back(std::move(face));
  }

  PIXELCLOTH_CHECK(!scan.faces.empty(),
                   file << ": no faces (" << scan.numVertices << " vertices, no 'f' lines); expected a surface mesh");
  const bool withTexcoords = !scan.faces[0].vt.empty();
  for (size_t f = 0; f < scan.faces.size(); ++f) {
    const ObjFace& face = scan.faces[f];
    for (int v : face.v) {
      PIXELCLOTH_CHECK(v < scan.numVertices, file << ": face " << f + 1 << " uses vertex " << v + 1
                                                  << ", but the file has " << scan.numVertices << " vertices (line "
                                                  << face.line << ")");
    }
    PIXELCLOTH_CHECK(face.vt.empty() != withTexcoords,
                     file << ": face " << f + 1 << (withTexcoords ? " has no" : " has")
                          << " texture coordinates, but face 1 " << (withTexcoords ? "has" : "has none")
                          << "; expected all faces or none (line " << face.line << ")");
    for (int t : face.vt) {
      PIXELCLOTH_CHECK(t < static_cast<int>(scan.texcoords.size()),
                       file << ": face " << f + 1 << " uses texture coordinate " << t + 1 << ", but the file has "
                            << scan.texcoords.size() << " (line " << face.line << ")");
    }
  }
  for (const auto& [f, normal] : normalUses) {
    PIXELCLOTH_CHECK(normal < scan.numNormals, file << ": face " << f + 1 << " uses normal " << normal + 1
                                                    << ", but the file has " << scan.numNormals << " (line "
                                                    << scan.faces[f].line << ")");
  }
  return scan;
}

Mesh readObj(const fs::path& path, const std::string& text) {
  const ObjScan scan = scanObj(path, text);
  long long expectedTriangles = 0;
  for (const ObjFace& face : scan.faces) expectedTriangles += static_cast<long long>(face.v.size()) - 2;

  OmMesh om;
  om.request_face_status();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::Default;
  std::istringstream in(text);
  PIXELCLOTH_CHECK(OpenMesh::IO::read_mesh(om, in, "obj", options), path.string()
                                                                        << ": OpenMesh could not read the file as OBJ");
  const long long flagged = countFlaggedFaces(om);
  if (flagged > 0 || static_cast<long long>(om.n_vertices()) != scan.numVertices ||
      static_cast<long long>(om.n_faces()) != expectedTriangles) {
    PIXELCLOTH_FAIL(
        nonManifoldMessage(path, flagged + std::max(0LL, expectedTriangles - static_cast<long long>(om.n_faces()))));
  }

  Mesh mesh;
  mesh.V.resize(om.n_vertices(), 3);
  for (auto v : om.vertices()) {
    const auto& p = om.point(v);
    mesh.V.row(v.idx()) << p[0], p[1], p[2];
  }
  const bool withTexcoords = !scan.faces[0].vt.empty();
  mesh.F.resize(expectedTriangles, 3);
  if (withTexcoords) {
    mesh.UV.resize(static_cast<Eigen::Index>(scan.texcoords.size()), 2);
    for (size_t i = 0; i < scan.texcoords.size(); ++i) mesh.UV.row(i) = scan.texcoords[i].transpose();
    mesh.FUV.resize(expectedTriangles, 3);
  }
  int row = 0;
  for (const ObjFace& face : scan.faces) {
    for (size_t k = 1; k + 1 < face.v.size(); ++k, ++row) {
      const int expected[3] = {face.v[0], face.v[k], face.v[k + 1]};
      // OpenMesh adds the fan triangles in this order; check it did, since FUV rows rely on it.
      int found[3], n = 0;
      for (auto v : om.fv_range(om.face_handle(row))) found[n++ % 3] = v.idx();
      int r = 0;
      while (r < 3 && found[r] != expected[0]) ++r;
      if (n != 3 || r == 3 || found[(r + 1) % 3] != expected[1] || found[(r + 2) % 3] != expected[2]) {
        throw std::logic_error(path.string() + ": OpenMesh's triangle " + std::to_string(row) +
                               " does not match the fan triangulation of the file's faces");
      }
      mesh.F.row(row) << expected[0], expected[1], expected[2];
      if (withTexcoords) mesh.FUV.row(row) << face.vt[0], face.vt[k], face.vt[k + 1];
    }
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------------------------
// PLY / OFF: OpenMesh parses; the counts the header declares are compared with what it built.

struct DeclaredCounts {
  long long vertices = -1;  // -1: unknown
  long long faces = -1;
};

DeclaredCounts plyCounts(const fs::path& path, const std::string& bytes) {
  std::istringstream in(bytes);
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  PIXELCLOTH_CHECK(line == "ply", path.string() << ": not a PLY file (it does not start with 'ply')");
  DeclaredCounts counts;
  bool ended = false, ascii = false;
  std::string element;
  long long minimumTokens = 0, elementCount = 0;  // ascii only: each property is at least one token, a list two
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") {
      ended = true;
      break;
    }
    if (word == "format") {
      words >> word;
      ascii = word == "ascii";
    } else if (word == "element") {
      elementCount = -1;
      words >> element >> elementCount;
      PIXELCLOTH_CHECK(words && elementCount >= 0, path.string() << ": malformed PLY header line '" << line << "'");
      if (element == "vertex") counts.vertices = elementCount;
      if (element == "face") counts.faces = elementCount;
    } else if (word == "property") {
      words >> word;
      minimumTokens += elementCount * (word == "list" ? (element == "face" ? 4 : 1) : 1);
    }
  }
  PIXELCLOTH_CHECK(ended, path.string() << ": malformed PLY header (no 'end_header')");
  PIXELCLOTH_CHECK(counts.vertices >= 0, path.string() << ": the PLY header declares no 'element vertex'");
  PIXELCLOTH_CHECK(counts.faces > 0, path.string() << ": no faces (the PLY header declares no faces)");
  if (ascii) {
    // OpenMesh's ascii reader builds faces from stale numbers when the data stops early: count the tokens first.
    long long tokens = 0;
    for (std::string token; in >> token;) ++tokens;
    PIXELCLOTH_CHECK(tokens >= minimumTokens, path.string()
                                                  << ": truncated: the header declares " << counts.vertices
                                                  << " vertices and " << counts.faces << " faces, which need at least "
                                                  << minimumTokens << " numbers, but the file has " << tokens);
  }
  return counts;
}

DeclaredCounts offCounts(const fs::path& path, const std::string& bytes) {
  std::istringstream in(bytes);
  std::string keyword;
  in >> keyword;
  PIXELCLOTH_CHECK(keyword.size() >= 3 && keyword.compare(keyword.size() - 3, 3, "OFF") == 0,
                   path.string() << ": not an OFF file (it does not start with 'OFF')");
  std::string rest;
  std::getline(in, rest);
  DeclaredCounts counts;
  if (rest.find("BINARY") != std::string::npos) return counts;  // counts are binary: rely on the checks after reading
  std::string token;
  while (in >> token && token[0] == '#') std::getline(in, rest);  // comment lines
  long vertices = -1;
  long long faces = -1;
  PIXELCLOTH_CHECK(
      parseIndex(token, vertices) && (in >> faces) && vertices >= 0 && faces >= 0,
      path.string() << ": malformed OFF header: expected the vertex and face counts after '" << keyword << "'");
  PIXELCLOTH_CHECK(faces > 0, path.string() << ": no faces (the OFF header declares 0 faces)");
  counts.vertices = vertices;
  counts.faces = faces;
  // OpenMesh's reader builds faces from stale numbers when the data stops early: count the tokens first (3 per vertex,
  // at least 4 per face).
  long long tokens = 0;
  for (std::string token; in >> token;) tokens += token[0] != '#';
  PIXELCLOTH_CHECK(tokens >= 3 * vertices + 4 * faces,
                   path.string() << ": truncated: the header declares " << vertices << " vertices and " << faces
                                 << " faces, which need at least " << 3 * vertices + 4 * faces
                                 << " numbers, but the file has " << tokens);
  return counts;
}

Mesh readPlyOrOff(const fs::path& path, const std::string& bytes, Format format) {
  const DeclaredCounts declared = format == Format::Ply ? plyCounts(path, bytes) : offCounts(path, bytes);
  OmMesh om;
  om.request_face_status();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::Default;
  std::istringstream in(bytes);
  bool ok = false;
  try {
    ok = OpenMesh::IO::read_mesh(om, in, extensionOf(format), options);
  } catch (const std::exception& e) {
    PIXELCLOTH_FAIL(path.string() << ": OpenMesh could not read the file (" << e.what() << ")");
  }
  PIXELCLOTH_CHECK(ok, path.string() << ": OpenMesh could not read the file as "
                                     << (format == Format::Ply ? "PLY" : "OFF") << ": it is malformed or truncated");
  const long long nv = static_cast<long long>(om.n_vertices()), nf = static_cast<long long>(om.n_faces());
  const long long flagged = countFlaggedFaces(om);
  if (flagged > 0 || (declared.vertices >= 0 && nv > declared.vertices)) {
    PIXELCLOTH_FAIL(nonManifoldMessage(path, flagged));
  }
  PIXELCLOTH_CHECK(declared.vertices < 0 || nv == declared.vertices,
                   path.string() << ": the header declares " << declared.vertices << " vertices, but only " << nv
                                 << " could be read: the file is truncated or malformed");
  // Polygons become several triangles, so only a shortfall is certain to be a fault.
  PIXELCLOTH_CHECK(declared.faces < 0 || nf >= declared.faces,
                   path.string() << ": the header declares " << declared.faces << " faces, but only " << nf
                                 << " triangles could be built: the file is truncated, malformed or not manifold");
  Mesh mesh;
  mesh.V.resize(nv, 3);
  for (auto v : om.vertices()) {
    const auto& p = om.point(v);
    mesh.V.row(v.idx()) << p[0], p[1], p[2];
  }
  mesh.F.resize(nf, 3);
  for (auto f : om.faces()) {
    int k = 0;
    for (auto v : f.vertices()) mesh.F(f.idx(), k++) = v.idx();
  }
  return mesh;
}

}  // namespace

Mesh readMesh(const fs::path& path) {
  const Format format = formatOf(path);
  const std::string bytes = readTextFile(path);
  silenceOpenMesh();
  Mesh mesh = format == Format::Obj ? readObj(path, bytes) : readPlyOrOff(path, bytes, format);
  mesh.validate(path.string());
  return mesh;
}

void writeMesh(const fs::path& path, const Mesh& mesh) {
  const Format format = formatOf(path);
  mesh.validate(path.string());
  silenceOpenMesh();

  OmMesh om;
  const bool withTexcoords = format == Format::Obj && mesh.hasUV();
  if (withTexcoords) om.request_halfedge_texcoords2D();
  if (!withTexcoords && mesh.hasUV()) {
    PIXELCLOTH_WARN(path.string() << ": " << (format == Format::Ply ? "PLY" : "OFF")
                                  << " files do not hold per-corner texture coordinates; they were not written (use "
                                     ".obj to keep them)");
  }
  om.reserve(mesh.V.rows(), mesh.F.rows() * 3 / 2 + mesh.V.rows(), mesh.F.rows());
  std::vector<OmMesh::VertexHandle> handles(mesh.V.rows());
  for (int i = 0; i < mesh.V.rows(); ++i)
    handles[i] = om.add_vertex(OmMesh::Point(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)));
  for (int f = 0; f < mesh.F.rows(); ++f) {
    auto face = om.add_face(handles[mesh.F(f, 0)], handles[mesh.F(f, 1)], handles[mesh.F(f, 2)]);
    PIXELCLOTH_CHECK(face.is_valid(), path.string() << ": cannot write face " << f << " (" << mesh.F(f, 0) << ", "
                                                    << mesh.F(f, 1) << ", " << mesh.F(f, 2)
                                                    << ") through OpenMesh: the mesh is not manifold (e.g. an edge "
                                                       "shared by more than two faces) or not consistently oriented");
    if (!withTexcoords) continue;
    for (auto h : face.halfedges()) {
      const int k = h.to().idx() == mesh.F(f, 0) ? 0 : h.to().idx() == mesh.F(f, 1) ? 1 : 2;
      const int t = mesh.FUV(f, k);
      om.set_texcoord2D(h, OmMesh::TexCoord2D(static_cast<float>(mesh.UV(t, 0)), static_cast<float>(mesh.UV(t, 1))));
    }
  }

  if (withTexcoords) {
    // OpenMesh's OBJ writer emits the texture coordinate of every halfedge, boundary ones (which belong to no face)
    // included; give those the coordinate of the corner they leave from, never uninitialised memory.
    for (auto h : om.halfedges()) {
      if (!h.is_boundary()) continue;
      om.set_texcoord2D(h, h.opp().is_boundary() ? OmMesh::TexCoord2D(0, 0) : om.texcoord2D(h.opp().prev()));
    }
  }

  OpenMesh::IO::Options options = OpenMesh::IO::Options::Default;
  if (withTexcoords) options += OpenMesh::IO::Options::FaceTexCoord;
  if (format == Format::Ply) {
    options += OpenMesh::IO::Options::Binary;
    options += OpenMesh::IO::Options::LSB;
  }
  writeAtomically(path, [&](const fs::path& temporary) {
    // The stream overload: OpenMesh picks the writer from the name, and the temporary name ends in ".tmp-<pid>".
    std::ofstream out(temporary, std::ios::binary);
    PIXELCLOTH_CHECK(out, path.string() << ": cannot open for writing");
    PIXELCLOTH_CHECK(OpenMesh::IO::write_mesh(om, out, extensionOf(format), options, kFloatDigits),
                     path.string() << ": OpenMesh could not write the mesh");
    out.close();
    PIXELCLOTH_CHECK(out, path.string() << ": write failed (disk full?)");
  });
}

}  // namespace pixelcloth::core
