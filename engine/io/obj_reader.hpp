// SPDX-License-Identifier: MIT
// Wavefront OBJ reading for example-pose sequences: `v`, `vt`, `vn` and `f` lines (triangles, quads,
// any polygon; `a`, `a/t`, `a//n`, `a/t/n` corners; negative relative indices), CRLF or LF, exponent
// notation, no final newline. Everything else (g, o, s, usemtl, mtllib, comments) is skipped.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "example_set.hpp"

namespace odeskin {

struct ObjMesh {
  std::vector<Vec3> positions;
  FaceList faces;
  // `vt` lines (u, v as written: OBJ's v runs up the image) and each face corner's index into them,
  // parallel to faces.indices. Both empty when the faces name none, or when they cannot be kept:
  // texcoord_warning then says why, naming the file and line. A broken texture mapping never stops
  // a fit, which needs only the positions.
  std::vector<Vec2> texcoords;
  std::vector<std::uint32_t> corner_texcoords;
  std::string texcoord_warning;
  // The same for `vn` lines; every normal a corner names is finite and not zero (isUsableNormal).
  std::vector<Vec3> normals;
  std::vector<std::uint32_t> corner_normals;
  std::string normal_warning;
};

// kIoError naming the path when it cannot be read; kParseError naming path and line for a malformed
// or non-finite number, a face index 0 or out of range, a face with fewer than 3 corners, or a
// file without vertices or faces. Problems with `vt` and `vn` (a bad number, an index out of range,
// corners with and without one) only drop them, with the warning above.
Result<ObjMesh> readObj(const std::filesystem::path& path);
// readObj on text already in memory; `source` names it in the messages (readObj passes the path).
Result<ObjMesh> parseObj(const std::string& text, const std::string& source);

// The render vertices an OBJ's corners make: one per distinct (v, vt, vn) in the order the faces
// first name them, with their UVs (v turned to run down the image, as RenderLayout's do) and
// normals, and obj_order set. Empty when the mesh kept neither texture coordinates nor normals.
RenderLayout objRenderLayout(const ObjMesh& mesh);
// The mesh's texcoord and normal warnings as lines a command prints ("texture coordinates (vt) are
// not kept: FILE:LINE: why"), or none.
std::vector<std::string> objLayoutWarnings(const ObjMesh& mesh);

// K >= 2 OBJ files of one mesh as example poses. Every pose must have the first pose's vertex count
// and face list (kInvalidArgument naming the first differing pose file and, for faces, the face
// number and both versions). The topology must be manifold (OpenMesh; buildPolyMesh's errors).
// `bind` (optional): a rest mesh with the same topology; the bind mesh X is then that mesh, else
// X = pose 0. Labels are the file names. readObj's errors pass through; fewer than 2 poses, and a
// bind mesh that differs (named like a differing pose), are kInvalidArgument. No rig is attached.
// The bind mesh's `vt` and `vn` (when it has any kept, else the first pose's) become the render
// layout (objRenderLayout), so outputs keep the texture mapping; the readers' warnings about the
// file they came from land in ExampleSet::warnings.
Result<ExampleSet> readObjSequence(std::span<const std::filesystem::path> poses, const std::filesystem::path* bind = nullptr);

}  // namespace odeskin
