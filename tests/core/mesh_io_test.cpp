// Mesh files through OpenMesh: round trips (OBJ with per-corner UVs and seams, binary PLY, OFF), the polygon and
// non-manifold policies, and the error each malformed input gives.
#include "pixelcloth/core/mesh_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace fs = std::filesystem;

namespace {

fs::path writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A 3x2 grid of vertices, 4 triangles, cut along the middle column in UV space: the two middle vertices have
// different UVs in the left and right faces (a seam).
pc::Mesh seamedGrid() {
  pc::Mesh mesh;
  mesh.V.resize(6, 3);
  mesh.V << 0, 0, 0.1, 0.5, 0, 0.2, 1, 0, 0.3, 0, 0.5, 0.4, 0.5, 0.5, 0.123456, 1, 0.5, -0.25;
  mesh.F.resize(4, 3);
  mesh.F << 0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4;
  mesh.UV.resize(8, 2);
  mesh.UV << 0, 0, 0.25, 0, 0, 0.25, 0.25, 0.25,  // left half
      0.75, 0, 1.0, 0, 0.75, 0.25, 1.0, 0.25;     // right half, shifted: vertices 1 and 4 appear twice
  mesh.FUV.resize(4, 3);
  mesh.FUV << 0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6;
  return mesh;
}

void expectSameCornerUVs(const pc::Mesh& a, const pc::Mesh& b) {
  ASSERT_TRUE(a.hasUV());
  ASSERT_TRUE(b.hasUV());
  ASSERT_EQ(a.F.rows(), b.F.rows());
  for (int f = 0; f < a.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR((a.UV.row(a.FUV(f, k)) - b.UV.row(b.FUV(f, k))).norm(), 0.0, 1e-7) << "face " << f << " corner " << k;
    }
  }
}

}  // namespace

TEST(MeshIo, ObjRoundTripKeepsOrderAndPerCornerUVsAcrossSeams) {
  fs::path dir = pixelcloth::testing::freshDir("obj");
  pc::Mesh mesh = seamedGrid();
  pc::writeMesh(dir / "grid.obj", mesh);
  // Every vt line is one of the mesh's texture coordinates: OpenMesh also writes those of boundary halfedges, which
  // once came out as uninitialised memory (NaN, 1e34) on open meshes.
  std::istringstream lines(pc::readTextFile(dir / "grid.obj"));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("vt ", 0) != 0) continue;
    std::istringstream values(line.substr(3));
    double u = 0, v = 0;
    values >> u >> v;
    EXPECT_TRUE(std::isfinite(u) && std::isfinite(v) && u >= 0 && u <= 1 && v >= 0 && v <= 0.25) << line;
  }
  pc::Mesh back = pc::readMesh(dir / "grid.obj");
  ASSERT_EQ(back.V.rows(), mesh.V.rows());
  EXPECT_LT((back.V - mesh.V).cwiseAbs().maxCoeff(), 1e-7);  // float precision, same vertex order
  EXPECT_EQ(back.F, mesh.F);                                 // same faces, same order, same corners
  expectSameCornerUVs(mesh, back);
  // The seam survived: vertex 4 has different UVs in face 0 (left) and face 3 (right).
  EXPECT_GT((back.UV.row(back.FUV(0, 2)) - back.UV.row(back.FUV(3, 2))).norm(), 0.4);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temporary left
}

TEST(MeshIo, PlyIsBinaryLittleEndianAndRoundTrips) {
  fs::path dir = pixelcloth::testing::freshDir("ply");
  pc::Mesh mesh = seamedGrid();
  mesh.vertexAttributes["weight"] = Eigen::MatrixXd::Ones(6, 1);
  pc::writeMesh(dir / "grid.PLY", mesh);  // extension is case-insensitive
  std::string bytes = pc::readTextFile(dir / "grid.PLY");
  EXPECT_NE(bytes.find("format binary_little_endian 1.0"), std::string::npos);
  pc::Mesh back = pc::readMesh(dir / "grid.PLY");
  EXPECT_LT((back.V - mesh.V).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_EQ(back.F, mesh.F);
  EXPECT_FALSE(back.hasUV());                  // PLY carries geometry only
  EXPECT_TRUE(back.vertexAttributes.empty());  // attributes never go through files
}

TEST(MeshIo, OffRoundTrips) {
  fs::path dir = pixelcloth::testing::freshDir("off");
  pc::Mesh mesh = seamedGrid();
  pc::writeMesh(dir / "grid.off", mesh);
  pc::Mesh back = pc::readMesh(dir / "grid.off");
  EXPECT_LT((back.V - mesh.V).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_EQ(back.F, mesh.F);
}

TEST(MeshIo, ReadsAsciiPly) {
  fs::path dir = pixelcloth::testing::freshDir("asciiply");
  writeFile(dir / "t.ply",
            "ply\nformat ascii 1.0\ncomment hand written\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  pc::Mesh mesh = pc::readMesh(dir / "t.ply");
  ASSERT_EQ(mesh.numVertices(), 4);
  ASSERT_EQ(mesh.numFaces(), 2);
  EXPECT_EQ(mesh.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(mesh.V.row(2), Eigen::RowVector3d(1, 1, 0));
}

TEST(MeshIo, QuadsAndPolygonsAreFanTriangulatedWithTheirUVs) {
  fs::path dir = pixelcloth::testing::freshDir("quad");
  // A quad and a pentagon sharing the edge 2-3, each with its own UVs.
  writeFile(dir / "poly.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nv 1.5 2 0\n"
            "vt 0.1 0.1\nvt 0.9 0.1\nvt 0.9 0.9\nvt 0.1 0.9\nvt 0.2 0.3\nvt 0.4 0.5\nvt 0.6 0.7\n"
            "f 1/1 2/2 3/3 4/4\nf 2/2 5/5 6/6 7/7 3/3\n");
  pc::Mesh mesh = pc::readMesh(dir / "poly.obj");
  ASSERT_EQ(mesh.numFaces(), 2 + 3);
  Eigen::MatrixX3i expectedF(5, 3);
  expectedF << 0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 6, 1, 6, 2;
  EXPECT_EQ(mesh.F, expectedF);
  ASSERT_TRUE(mesh.hasUV());
  Eigen::MatrixX3i expectedFUV(5, 3);
  expectedFUV << 0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 6, 1, 6, 2;
  EXPECT_EQ(mesh.FUV, expectedFUV);
  EXPECT_EQ(mesh.UV.row(3), Eigen::RowVector2d(0.1, 0.9));
}

TEST(MeshIo, IndexFormsAndRelativeIndicesAgree) {
  fs::path dir = pixelcloth::testing::freshDir("forms");
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n";
  writeFile(dir / "plain.obj", vertices + "f 1/1 2/2 3/3\n");
  writeFile(dir / "relative.obj", vertices + "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n");
  writeFile(dir / "normals.obj", vertices + "f 1//1 2//1 3//1\n");
  pc::Mesh plain = pc::readMesh(dir / "plain.obj");
  pc::Mesh relative = pc::readMesh(dir / "relative.obj");
  pc::Mesh normals = pc::readMesh(dir / "normals.obj");
  EXPECT_EQ(plain.F, relative.F);
  EXPECT_EQ(plain.FUV, relative.FUV);
  EXPECT_EQ(plain.F, normals.F);
  EXPECT_FALSE(normals.hasUV());
}

TEST(MeshIo, NonManifoldObjIsRefused) {
  fs::path dir = pixelcloth::testing::freshDir("nonmanifold");
  // Three triangles share the edge 1-2: OpenMesh would duplicate the third one's vertices.
  writeFile(dir / "fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / "fin.obj"); });
  EXPECT_NE(message.find((dir / "fin.obj").string() +
                         ": 1 faces could not be added without duplicating vertices: the mesh is not manifold (e.g. "
                         "an edge shared by more than two faces)"),
            std::string::npos)
      << message;
}

TEST(MeshIo, NonManifoldPlyIsRefusedAndCannotBeWritten) {
  fs::path dir = pixelcloth::testing::freshDir("nonmanifoldply");
  writeFile(dir / "fin.ply",
            "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 3\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  EXPECT_NE(pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / "fin.ply"); }).find("not manifold"),
            std::string::npos);

  pc::Mesh fin;
  fin.V.resize(5, 3);
  fin.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  fin.F.resize(3, 3);
  fin.F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::writeMesh(dir / "out.obj", fin); });
  EXPECT_NE(message.find("cannot write face 2"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

TEST(MeshIo, ObjFaultsAreNamedWithFileAndPlace) {
  fs::path dir = pixelcloth::testing::freshDir("faults");
  auto errorFor = [&](const std::string& name, const std::string& text) {
    writeFile(dir / name, text);
    return pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / name); });
  };
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  std::string file = (dir / "garment.obj").string();
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2 3\nf 1 3 9\n"),
            file + ": face 2 uses vertex 9, but the file has 4 vertices (line 6)");
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2 -7\n"),
            file + ": face 1 uses vertex -7, but only 4 precede it (line 5)");
  // strtol saturates: -99...9 is LONG_MIN, whose negation overflowed (found by fuzzing).
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2 -99999999999999999999999\n"),
            file + ": face 1 uses vertex -9223372036854775808, but only 4 precede it (line 5)");
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2 0\n"),
            file + ": face 1 uses vertex 0, but OBJ indices start at 1 (line 5)");
  EXPECT_EQ(errorFor("garment.obj", quad + "vt 0 0\nf 1/1 2/2 3/1\n"),
            file + ": face 1 uses texture coordinate 2, but the file has 1 (line 6)");
  EXPECT_EQ(errorFor("garment.obj", quad + "vt 0 0\nf 1/1 2 3/1\n"),
            file + ": face 1 gives texture coordinates for some corners only; expected all or none (line 6)");
  EXPECT_EQ(errorFor("garment.obj", quad + "vt 0 0\nf 1/1 2/1 3/1\nf 1 3 4\n"),
            file + ": face 2 has no texture coordinates, but face 1 has; expected all faces or none (line 7)");
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2 2\n"), file + ": face 1 repeats vertex 2 (line 5)");
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2\n"), file + ": face 1 has 2 corners, expected at least 3 (line 5)");
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2 x\n"),
            file + ": face 1 has 'x' where a vertex index was expected (line 5)");
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1 2 3/1/1/1\n"),
            file + ": face 1 has a malformed corner '3/1/1/1', expected v, v/vt, v//vn or v/vt/vn (line 5)");
  EXPECT_EQ(errorFor("garment.obj", quad + "f 1//2 2//1 3//1\nvn 0 0 1\n"),
            file + ": face 1 uses normal 2, but the file has 1 (line 5)");

  std::string body = (dir / "body.obj").string();
  EXPECT_EQ(errorFor("body.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"),
            body + ": vertex 2 has a non-finite coordinate (line 2)");
  EXPECT_EQ(errorFor("body.obj", "v 0 0 0\nv 1 0 0\nv 0 1 1e999\nf 1 2 3\n"),
            body + ": vertex 3 has a non-finite coordinate (line 3)");
  EXPECT_EQ(errorFor("body.obj", "v 0 0 0\nv 1e300 1e300 1e300\nv 0 1 0\nf 1 2 3\n"),
            body + ": vertex 2 has the coordinate 1e300, beyond 1e+09 in size (line 2)");
  EXPECT_EQ(errorFor("body.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n"),
            body + ": vertex 2 has 'zero' where a number was expected (line 2)");
  EXPECT_EQ(errorFor("body.obj", "v 0 0\n"), body + ": vertex 1 has 2 numbers, expected 3 (line 1)");
  EXPECT_EQ(errorFor("body.obj", quad + "# just points\n"),
            body + ": no faces (4 vertices, no 'f' lines); expected a surface mesh");
  EXPECT_EQ(errorFor("body.obj", std::string("v 0 0 0\n\0\x7f garbage", 17)),
            body + ": not a text OBJ file (it contains binary data)");
}

TEST(MeshIo, MissingGarbageAndTruncatedFilesAreNamed) {
  fs::path dir = pixelcloth::testing::freshDir("garbage");
  std::string missing = pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / "absent.obj"); });
  EXPECT_NE(missing.find((dir / "absent.obj").string() + ": no such file"), std::string::npos) << missing;

  std::string garbage;
  for (int i = 0; i < 3000; ++i) garbage.push_back(static_cast<char>((i * 7919 + 13) % 251 + 1));
  for (const char* name : {"g.obj", "g.ply", "g.off"}) {
    writeFile(dir / name, garbage);
    std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / name); });
    EXPECT_EQ(message.rfind((dir / name).string() + ": ", 0), 0u) << message;
  }

  pc::Mesh mesh = seamedGrid();
  for (const char* name : {"t.ply", "t.off"}) {
    pc::writeMesh(dir / name, mesh);
    std::string bytes = pc::readTextFile(dir / name);
    writeFile(dir / name, bytes.substr(0, bytes.size() - 20));
    std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / name); });
    EXPECT_EQ(message.rfind((dir / name).string() + ": ", 0), 0u) << message;
  }
}

TEST(MeshIo, UnsupportedExtensionListsTheAcceptedOnes) {
  fs::path dir = pixelcloth::testing::freshDir("ext");
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::writeMesh(dir / "m.stl", seamedGrid()); });
  EXPECT_NE(message.find("unsupported mesh format '.stl'; expected one of .obj, .ply, .off"), std::string::npos)
      << message;
  EXPECT_NE(
      pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / "m"); }).find("expected one of .obj, .ply, .off"),
      std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "m.stl"));
}

TEST(MeshIo, InvalidMeshIsNotWritten) {
  fs::path dir = pixelcloth::testing::freshDir("invalid");
  pc::Mesh mesh = seamedGrid();
  mesh.F(2, 1) = 17;
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::writeMesh(dir / "bad.obj", mesh); });
  EXPECT_NE(message.find("face 3 uses vertex 18"), std::string::npos) << message;  // counted from 1
  EXPECT_TRUE(fs::is_empty(dir));
}

// Inputs that hung OpenMesh's own readers (found by fuzzing, docs/reliability.md): the file is read by our scan
// first, which names the fault.
TEST(MeshIo, FilesThatHungOpenMeshAreRefusedWithTheirFault) {
  const fs::path off = pixelcloth::testing::asset("fuzz_mesh_off_hang.off");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readMesh(off); }),
            off.string() + ": face 1 declares 0 corners, but a face needs at least 3 (line 9)");
  const fs::path ply = pixelcloth::testing::asset("fuzz_mesh_ply_hang.ply");
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readMesh(ply); });
  EXPECT_EQ(message.rfind(ply.string() + ": malformed PLY header line 8 'property list uchar ??????ndices': expected "
                                         "'property list COUNT_TYPE VALUE_TYPE NAME'",
                          0),
            0u)
      << message;
}

TEST(MeshIo, PlyAndOffStructureFaultsAreNamed) {
  fs::path dir = pixelcloth::testing::freshDir("plyoff");
  auto errorFor = [&](const std::string& name, const std::string& text) {
    writeFile(dir / name, text);
    return pixelcloth::testing::inputErrorOf([&] { pc::readMesh(dir / name); });
  };
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string ply = (dir / "m.ply").string();
  EXPECT_EQ(errorFor("m.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
            ply + ": truncated or malformed: face 1 of 1 (counting from 1), property 'vertex_indices': corner 3 is "
                  "vertex 7 (counting from 0), but the file has 3 vertices");
  EXPECT_EQ(errorFor("m.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
            ply + ": truncated or malformed: face 1 of 1 (counting from 1), property 'vertex_indices': the data ends, "
                  "expected a int");
  EXPECT_EQ(errorFor("m.ply", header + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"),
            ply + ": truncated or malformed: vertex 2 of 3 (counting from 1), property 'y': 'x' where a float was "
                  "expected");
  EXPECT_EQ(errorFor("m.ply", header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
            ply + ": truncated or malformed: face 1 of 1 (counting from 1), property 'vertex_indices': a face of 2 "
                  "corners, expected at least 3");
  EXPECT_EQ(errorFor("m.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n"),
            ply + ": face 1 repeats vertex 1 (the file's numbering, from 0)");
  std::string noZ = header;
  noZ.replace(noZ.find("property float z\n"), 17, "");
  EXPECT_EQ(errorFor("m.ply", noZ + "0 0\n1 0\n0 1\n3 0 1 2\n"), ply + ": the PLY vertex element has no 'z' property");

  const std::string off = (dir / "m.off").string();
  EXPECT_EQ(errorFor("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            off + ": face 1 has corner '3', expected a vertex number from 0 to 2 (line 6)");
  EXPECT_EQ(errorFor("m.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
            off + ": vertex 2 has 2 numbers, expected at least 3 (line 4)");
  EXPECT_EQ(errorFor("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n"),
            off + ": face 1 declares 4 corners, but 3 follow (line 6)");
  EXPECT_EQ(errorFor("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n/ 0 1 2\n"),
            off + ": face 1 starts with '/' where its corner count was expected (line 6)");
  EXPECT_EQ(errorFor("m.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            off + ": truncated: the header declares 3 vertices and 2 faces, but the data ends at face 2");
  EXPECT_EQ(errorFor("m.off", "OFF BINARY\n"), off + ": binary OFF is not supported; save the mesh as ASCII OFF, PLY or OBJ");
  // Comments, counts on the keyword's line and colour numbers after a face are read.
  writeFile(dir / "ok.off", "OFF 3 1 0 # counts here\n# a comment\n0 0 0\n1 0 0 # colourless\n0 1 0\n3 0 1 2 255 0 0\n");
  pc::Mesh mesh = pc::readMesh(dir / "ok.off");
  EXPECT_EQ(mesh.numFaces(), 1);
  EXPECT_EQ(mesh.V.row(1), Eigen::RowVector3d(1, 0, 0));
}

TEST(MeshIo, ReadsBigEndianBinaryPlyWithExtraProperties) {
  fs::path dir = pixelcloth::testing::freshDir("bigendian");
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nproperty short flags\nend_header\n";
  auto put = [&](auto value) {
    unsigned char raw[sizeof(value)];
    std::memcpy(raw, &value, sizeof(value));
    for (size_t i = sizeof(value); i-- > 0;) bytes.push_back(static_cast<char>(raw[i]));  // most significant first
  };
  const float points[3][3] = {{0, 0, 0}, {1.5f, 0, 0}, {0, -2.25f, 0.5f}};
  for (const auto& p : points) {
    for (float c : p) put(c);
    put(static_cast<unsigned char>(200));
  }
  put(static_cast<unsigned char>(3));
  for (std::int32_t v : {0, 1, 2}) put(v);
  put(static_cast<std::int16_t>(-1));
  writeFile(dir / "be.ply", bytes);
  pc::Mesh mesh = pc::readMesh(dir / "be.ply");
  ASSERT_EQ(mesh.numVertices(), 3);
  ASSERT_EQ(mesh.numFaces(), 1);
  EXPECT_EQ(mesh.V.row(2), Eigen::RowVector3d(0, -2.25, 0.5));
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
}
