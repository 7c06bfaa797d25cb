// SPDX-License-Identifier: MIT
// Wavefront OBJ reading for example-pose sequences: `v` and `f` lines (triangles, quads, any
// polygon; `a`, `a/t`, `a//n`, `a/t/n` corners; negative relative indices), CRLF or LF, exponent
// notation, no final newline. Everything else (vt, vn, g, o, s, usemtl, mtllib, comments) is skipped.
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
};

// kIoError naming the path when it cannot be read; kParseError naming path and line for a malformed
// or non-finite number, a face index 0 or out of range, a face with fewer than 3 corners, or a
// file without vertices or faces.
Result<ObjMesh> readObj(const std::filesystem::path& path);
// readObj on text already in memory; `source` names it in the messages (readObj passes the path).
Result<ObjMesh> parseObj(const std::string& text, const std::string& source);

// K >= 2 OBJ files of one mesh as example poses. Every pose must have the first pose's vertex count
// and face list (kInvalidArgument naming the first differing pose file and, for faces, the face
// number and both versions). The topology must be manifold (OpenMesh; buildPolyMesh's errors).
// `bind` (optional): a rest mesh with the same topology; the bind mesh X is then that mesh, else
// X = pose 0. Labels are the file names. readObj's errors pass through; fewer than 2 poses, and a
// bind mesh that differs (named like a differing pose), are kInvalidArgument. No rig is attached.
Result<ExampleSet> readObjSequence(std::span<const std::filesystem::path> poses, const std::filesystem::path* bind = nullptr);

}  // namespace odeskin
