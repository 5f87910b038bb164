#pragma once

#include <filesystem>

#include "pixelcloth/core/mesh.h"

namespace pixelcloth::core {

/// Reads a triangle mesh from .obj, .ply (ascii or binary) or .off, chosen by the extension (case-insensitive),
/// through OpenMesh. Throws `InputError` naming the file and the fault for: a missing or unreadable file, an
/// unsupported extension, garbage, a face index out of range, a non-finite coordinate, no faces, and a mesh
/// OpenMesh cannot hold without changing it (see below).
///
/// Policies:
/// - Polygons (quads, n-gons) are triangulated as a fan around their first corner: (c0, c1, c2), (c0, c2, c3), ...
///   in file order, so a quad becomes 2 triangles and an n-gon n - 2. Vertex order and face order are kept.
/// - Non-manifold input (an edge shared by more than two faces, inconsistently oriented neighbours, ...) is
///   refused: OpenMesh would silently duplicate vertices or drop faces to make it fit its halfedge structure.
/// - OBJ: per-corner texture coordinates (`vt`, `f v/vt`) fill `UV` (the file's `vt` table, in order) and `FUV`
///   (one row per triangle); seams (one vertex, different UVs in different faces) are kept. Either every face has
///   texture coordinates or none does. Normals (`vn`) are checked for range but not kept. Messages about an OBJ
///   use the file's own numbering (faces and vertices from 1, as written) and give the line.
/// - PLY / OFF carry positions and triangles only: no texture coordinates.
/// - `vertexAttributes` and `faceAttributes` never go through files (they come back empty).
/// - Positions pass through OpenMesh's readers and writers as 32-bit floats (about 0.1 micrometre at 1 m); OBJ
///   texture coordinates are read in double precision and written as floats.
Mesh readMesh(const std::filesystem::path& path);

/// Writes `mesh` (validated first) as .obj, .ply (binary little-endian) or .off, chosen by the extension
/// (case-insensitive), through OpenMesh, atomically (temporary name, then rename). OBJ keeps the per-corner
/// texture coordinates (`UV`, `FUV`; identical values are merged into one `vt`); PLY and OFF drop them (an
/// info line says so). Throws `InputError` for an unsupported extension, an invalid mesh, or a non-manifold mesh
/// OpenMesh cannot represent.
void writeMesh(const std::filesystem::path& path, const Mesh& mesh);

}  // namespace pixelcloth::core
