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
        // Beyond this, squared lengths and cross products overflow to inf: no mesh is that large in any unit.
        PIXELCLOTH_CHECK(std::abs(value) <= kMaxCoordinate, file << ": " << what << " " << number
                                                                 << " has the coordinate " << tokens[i] << ", beyond "
                                                                 << kMaxCoordinate << " in size (line " << line << ")");
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
      PIXELCLOTH_CHECK(raw >= -static_cast<long>(definedSoFar), file << ": face " << faceNumber << " uses " << what << " " << raw
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
// PLY / OFF: read here, not by OpenMesh's readers, which loop or build faces from stale numbers on malformed data
// (a hang found by fuzzing each format, docs/reliability.md). OpenMesh builds the mesh from what was read and refuses
// faces that are not manifold.

// The vertices (0-based) and polygons of a file.
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
};

// A PLY scalar type: its size in bytes and how to read it.
struct PlyType {
  std::string name;
  int size = 0;
  bool integer = false;
  bool isSigned = false;
};

bool plyTypeOf(const std::string& name, PlyType& type) {
  static const std::vector<PlyType> types = {
      {"char", 1, true, true},    {"int8", 1, true, true},     {"uchar", 1, true, false},  {"uint8", 1, true, false},
      {"short", 2, true, true},   {"int16", 2, true, true},    {"ushort", 2, true, false}, {"uint16", 2, true, false},
      {"int", 4, true, true},     {"int32", 4, true, true},    {"uint", 4, true, false},   {"uint32", 4, true, false},
      {"float", 4, false, true},  {"float32", 4, false, true}, {"double", 8, false, true}, {"float64", 8, false, true}};
  for (const PlyType& t : types) {
    if (t.name == name) {
      type = t;
      return true;
    }
  }
  return false;
}

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType count;  // lists only
  PlyType value;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

// Reads one value after another from a PLY body, in text or binary.
class PlyValues {
 public:
  PlyValues(const std::string& bytes, size_t begin, bool ascii, bool bigEndian)
      : bytes_(bytes), at_(begin), ascii_(ascii), bigEndian_(bigEndian) {}

  // False at the end of the data, or (text) when the next token is not a number of the type.
  bool next(const PlyType& type, double& value, std::string& found) {
    if (ascii_) {
      while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
      const size_t begin = at_;
      while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
      found = bytes_.substr(begin, std::min<size_t>(at_ - begin, 20));
      if (begin == at_) return false;
      return parseNumber(bytes_.substr(begin, at_ - begin), value) && (!type.integer || value == std::floor(value));
    }
    found.clear();
    if (bytes_.size() - at_ < static_cast<size_t>(type.size)) return false;
    unsigned char raw[8];
    for (int i = 0; i < type.size; ++i) raw[i] = static_cast<unsigned char>(bytes_[at_ + (bigEndian_ ? type.size - 1 - i : i)]);
    at_ += static_cast<size_t>(type.size);
    std::uint64_t bits = 0;
    for (int i = type.size - 1; i >= 0; --i) bits = bits << 8 | raw[i];
    if (!type.integer) {
      if (type.size == 4) {
        float f;
        const std::uint32_t b32 = static_cast<std::uint32_t>(bits);
        std::memcpy(&f, &b32, 4);
        value = f;
      } else {
        std::memcpy(&value, &bits, 8);
      }
    } else if (type.isSigned && (bits >> (8 * type.size - 1) & 1)) {
      value = static_cast<double>(static_cast<std::int64_t>(bits) - (std::int64_t{1} << (8 * type.size)));
    } else {
      value = static_cast<double>(bits);
    }
    return true;
  }

 private:
  const std::string& bytes_;
  size_t at_;
  bool ascii_;
  bool bigEndian_;
};

PolygonSoup scanPly(const fs::path& path, const std::string& bytes) {
  const std::string file = path.string();
  size_t at = 0;
  int lineNumber = 0;
  auto nextLine = [&](std::string& line) {
    if (at >= bytes.size()) return false;
    size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    line = bytes.substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    at = std::min(bytes.size(), end + 1);
    ++lineNumber;
    return true;
  };
  std::string line;
  PIXELCLOTH_CHECK(nextLine(line) && line == "ply", file << ": not a PLY file (it does not start with 'ply')");
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (nextLine(line)) {
    auto malformed = [&](const std::string& why) {
      std::string shown = line.substr(0, 60);
      for (char& c : shown) {
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
      }
      PIXELCLOTH_FAIL(file << ": malformed PLY header line " << lineNumber << " '" << shown << "': " << why);
    };
    std::istringstream words(line);
    std::string word, extra;
    words >> word;
    if (word == "end_header") {
      ended = true;
      break;
    }
    if (word.empty() || word == "comment" || word == "obj_info") continue;
    if (word == "format") {
      std::string version;
      words >> format >> version;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian") {
        malformed("expected the format ascii, binary_little_endian or binary_big_endian");
      }
    } else if (word == "element") {
      PlyElement element;
      if (!(words >> element.name >> element.count) || element.count < 0 || (words >> extra)) {
        malformed("expected 'element NAME COUNT'");
      }
      elements.push_back(element);
    } else if (word == "property") {
      if (elements.empty()) malformed("a property before any element");
      PlyProperty property;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string countType, valueType;
        property.list = true;
        if (!(words >> countType >> valueType >> property.name) || (words >> extra) ||
            !plyTypeOf(countType, property.count) || !plyTypeOf(valueType, property.value) || !property.count.integer) {
          malformed("expected 'property list COUNT_TYPE VALUE_TYPE NAME' with an integer COUNT_TYPE");
        }
      } else if (!plyTypeOf(type, property.value) || !(words >> property.name) || (words >> extra)) {
        malformed("expected 'property TYPE NAME' with TYPE one of char, uchar, short, ushort, int, uint, float, "
                  "double (or int8 ... float64)");
      }
      elements.back().properties.push_back(property);
    } else {
      malformed("expected format, element, property, comment or end_header");
    }
  }
  PIXELCLOTH_CHECK(ended, file << ": malformed PLY header (no 'end_header')");
  PIXELCLOTH_CHECK(!format.empty(), file << ": malformed PLY header (no 'format' line)");

  long long numVertices = -1, numFaces = -1;
  for (const PlyElement& element : elements) {
    if (element.name == "vertex") numVertices = element.count;
    if (element.name == "face") numFaces = element.count;
  }
  PIXELCLOTH_CHECK(numVertices >= 0, file << ": the PLY header declares no 'element vertex'");
  PIXELCLOTH_CHECK(numFaces > 0, file << ": no faces (the PLY header declares no faces)");
  PIXELCLOTH_CHECK(numVertices < (1LL << 31) && numFaces < (1LL << 31),
                   file << ": the PLY header declares " << numVertices << " vertices and " << numFaces
                        << " faces; at most 2^31 - 1 of each are supported");
  for (const PlyElement& element : elements) {
    if (element.name == "vertex") {
      for (const char* axis : {"x", "y", "z"}) {
        const bool has = std::any_of(element.properties.begin(), element.properties.end(),
                                     [&](const PlyProperty& p) { return !p.list && p.name == axis; });
        PIXELCLOTH_CHECK(has, file << ": the PLY vertex element has no '" << axis << "' property");
      }
    } else if (element.name == "face") {
      const bool has = std::any_of(element.properties.begin(), element.properties.end(), [](const PlyProperty& p) {
        return p.list && p.value.integer && (p.name == "vertex_indices" || p.name == "vertex_index");
      });
      PIXELCLOTH_CHECK(has, file << ": the PLY face element has no integer list 'vertex_indices'");
    }
  }

  // Walk every value of every element: the data must hold what the header declares, and faces must name vertices.
  PlyValues values(bytes, at, format == "ascii", format == "binary_big_endian");
  double value = 0;
  std::string found;
  PolygonSoup soup;
  for (const PlyElement& element : elements) {
    const bool isVertex = element.name == "vertex", isFace = element.name == "face";
    for (long long item = 0; item < element.count; ++item) {
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      std::vector<int> face;
      for (const PlyProperty& property : element.properties) {
        auto fault = [&](const std::string& what) {
          PIXELCLOTH_FAIL(file << ": truncated or malformed: " << element.name << " " << item + 1 << " of "
                               << element.count << " (counting from 1), property '" << property.name << "': " << what);
        };
        auto read = [&](const PlyType& type) {
          if (values.next(type, value, found)) return;
          if (found.empty()) fault("the data ends, expected a " + type.name);
          fault("'" + found + "' where a " + type.name + " was expected");
        };
        long long n = 1;
        if (property.list) {
          read(property.count);
          PIXELCLOTH_CHECK(value >= 0, file << ": " << element.name << " " << item + 1 << " has a list of " << value
                                            << " entries in '" << property.name << "'");
          n = static_cast<long long>(value);
        }
        const bool corners =
            isFace && property.list && (property.name == "vertex_indices" || property.name == "vertex_index");
        if (corners && n < 3) fault("a face of " + std::to_string(n) + " corners, expected at least 3");
        for (long long k = 0; k < n; ++k) {
          read(property.value);
          if (corners) {
            if (value < 0 || value >= static_cast<double>(numVertices)) {
              fault("corner " + std::to_string(k + 1) + " is vertex " + std::to_string(static_cast<long long>(value)) +
                    " (counting from 0), but the file has " + std::to_string(numVertices) + " vertices");
            }
            face.push_back(static_cast<int>(value));
          }
        }
        if (isVertex && !property.list && property.name.size() == 1 && property.name[0] >= 'x' &&
            property.name[0] <= 'z') {
          point[property.name[0] - 'x'] = value;
        }
      }
      if (isVertex) soup.points.push_back(point);
      if (isFace) soup.faces.push_back(std::move(face));
    }
  }
  return soup;
}

// An ASCII OFF file, line by line: the counts, then one line per vertex (at least three numbers; colours, normals
// or texture coordinates may follow) and one per face (the corner count, the corners, optional colour numbers).
PolygonSoup scanOff(const fs::path& path, const std::string& bytes) {
  const std::string file = path.string();
  std::istringstream in(bytes);
  std::string line;
  int lineNumber = 0;
  // The next line with something on it, comments removed, split into words.
  auto nextWords = [&](std::vector<std::string>& words) {
    while (std::getline(in, line)) {
      ++lineNumber;
      const size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      words.clear();
      std::istringstream split(line);
      for (std::string w; split >> w;) words.push_back(w);
      if (!words.empty()) return true;
    }
    return false;
  };
  std::vector<std::string> words;
  const bool hasKeyword = nextWords(words);
  const std::string keyword = hasKeyword ? words[0] : "";
  PIXELCLOTH_CHECK(keyword.size() >= 3 && keyword.compare(keyword.size() - 3, 3, "OFF") == 0,
                   file << ": not an OFF file (it does not start with 'OFF')");
  PIXELCLOTH_CHECK(std::find(words.begin(), words.end(), "BINARY") == words.end(),
                   file << ": binary OFF is not supported; save the mesh as ASCII OFF, PLY or OBJ");
  std::vector<std::string> countWords(words.begin() + 1, words.end());  // the counts may follow on the same line
  if (countWords.empty()) nextWords(countWords);
  long vertices = -1, faces = -1;
  PIXELCLOTH_CHECK(countWords.size() >= 2 && parseIndex(countWords[0], vertices) && parseIndex(countWords[1], faces) &&
                       vertices >= 0 && faces >= 0,
                   file << ": malformed OFF header: expected the vertex and face counts after '" << keyword << "'");
  PIXELCLOTH_CHECK(faces > 0, file << ": no faces (the OFF header declares 0 faces)");
  PIXELCLOTH_CHECK(vertices < (1L << 31) && faces < (1L << 31),
                   file << ": the OFF header declares " << vertices << " vertices and " << faces
                        << " faces; at most 2^31 - 1 of each are supported");
  PolygonSoup soup;
  auto truncated = [&](const std::string& what) {
    PIXELCLOTH_FAIL(file << ": truncated: the header declares " << vertices << " vertices and " << faces
                         << " faces, but the data ends at " << what);
  };
  double number = 0;
  for (long v = 0; v < vertices; ++v) {
    if (!nextWords(words)) truncated("vertex " + std::to_string(v + 1));
    PIXELCLOTH_CHECK(words.size() >= 3, file << ": vertex " << v + 1 << " has " << words.size()
                                             << " numbers, expected at least 3 (line " << lineNumber << ")");
    Eigen::Vector3d point;
    for (size_t k = 0; k < words.size(); ++k) {
      PIXELCLOTH_CHECK(parseNumber(words[k], number), file << ": vertex " << v + 1 << " has '" << words[k].substr(0, 20)
                                                           << "' where a number was expected (line " << lineNumber
                                                           << ")");
      if (k < 3) point[static_cast<Eigen::Index>(k)] = number;
    }
    soup.points.push_back(point);
  }
  for (long f = 0; f < faces; ++f) {
    if (!nextWords(words)) truncated("face " + std::to_string(f + 1));
    long corners = 0;
    PIXELCLOTH_CHECK(parseIndex(words[0], corners), file << ": face " << f + 1 << " starts with '" << words[0].substr(0, 20)
                                                         << "' where its corner count was expected (line "
                                                         << lineNumber << ")");
    PIXELCLOTH_CHECK(corners >= 3 && corners < static_cast<long>(words.size()),
                     file << ": face " << f + 1 << " declares " << corners << " corners, but "
                          << (corners < 3 ? "a face needs at least 3" : std::to_string(words.size() - 1) + " follow")
                          << " (line " << lineNumber << ")");
    std::vector<int> face;
    for (long k = 1; k <= corners; ++k) {
      long vertex = -1;
      PIXELCLOTH_CHECK(parseIndex(words[k], vertex) && vertex >= 0 && vertex < vertices,
                       file << ": face " << f + 1 << " has corner '" << words[k].substr(0, 20) << "', expected a vertex "
                            << "number from 0 to " << vertices - 1 << " (line " << lineNumber << ")");
      face.push_back(static_cast<int>(vertex));
    }
    soup.faces.push_back(std::move(face));
    for (size_t k = static_cast<size_t>(corners) + 1; k < words.size(); ++k) {
      PIXELCLOTH_CHECK(parseNumber(words[k], number), file << ": face " << f + 1 << " has '" << words[k].substr(0, 20)
                                                           << "' where a colour number was expected (line "
                                                           << lineNumber << ")");
    }
  }
  return soup;
}

Mesh readPlyOrOff(const fs::path& path, const std::string& bytes, Format format) {
  const PolygonSoup soup = format == Format::Ply ? scanPly(path, bytes) : scanOff(path, bytes);
  OmMesh om;
  for (const Eigen::Vector3d& p : soup.points) om.add_vertex(OmMesh::Point(p.x(), p.y(), p.z()));
  // OpenMesh refuses a face that would make an edge or a vertex non-manifold (or repeats a corner); a polygon is
  // fan-triangulated.
  long long refused = 0;
  std::vector<OmMesh::VertexHandle> corners;
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const std::vector<int>& face = soup.faces[f];
    for (size_t k = 0; k < face.size(); ++k) {
      PIXELCLOTH_CHECK(std::find(face.begin() + static_cast<long>(k) + 1, face.end(), face[k]) == face.end(),
                       path.string() << ": face " << f + 1 << " repeats vertex " << face[k]
                                     << " (the file's numbering, from 0)");
    }
    corners.clear();
    for (int v : face) corners.push_back(om.vertex_handle(static_cast<unsigned>(v)));
    refused += !om.add_face(corners).is_valid();
  }
  if (refused > 0) PIXELCLOTH_FAIL(nonManifoldMessage(path, refused));
  Mesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(soup.points.size()), 3);
  for (size_t v = 0; v < soup.points.size(); ++v) mesh.V.row(static_cast<Eigen::Index>(v)) = soup.points[v].transpose();
  mesh.F.resize(static_cast<Eigen::Index>(om.n_faces()), 3);
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
