// SPDX-License-Identifier: MIT
// Stanford PLY output for meshes coloured per vertex, such as error heat maps, which MeshLab,
// Blender and CloudCompare open with their colours: binary little-endian, float x y z, optional
// uchar red green blue and float quality (MeshLab's per-vertex scalar, here the error), then the
// faces as a uchar count and int indices.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "../core/status.hpp"
#include "../core/types.hpp"

namespace odeskin {

struct PlyVertexData {
  std::span<const std::array<std::uint8_t, 3>> colours;  // empty, or one per vertex
  std::span<const float> quality;                        // empty, or one per vertex
};

// Writes through writeFileAtomically. kInvalidArgument naming the path for a colour or quality
// count that is not the vertex count, a face with fewer than 3 or more than 255 corners, an index
// out of range, or a coordinate that is not a finite float32; kIoError when it cannot be written.
// `comment` goes into the header (one line, no line breaks).
Status writePly(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces,
                const PlyVertexData& data = {}, const std::string& comment = {});

}  // namespace odeskin
