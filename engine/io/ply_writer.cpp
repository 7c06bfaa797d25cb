// SPDX-License-Identifier: MIT
#include "ply_writer.hpp"

#include <cmath>
#include <limits>

#include "../core/number_text.hpp"
#include "little_endian.hpp"
#include "obj_io.hpp"

namespace odeskin {

Status writePly(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces,
                const PlyVertexData& data, const std::string& comment) {
  const std::string where = path.string() + ": ";
  const std::size_t n = positions.size();
  if (!data.colours.empty() && data.colours.size() != n) {
    return invalidArgument(where + std::to_string(data.colours.size()) + " colours for " + std::to_string(n) + " vertices");
  }
  if (!data.quality.empty() && data.quality.size() != n) {
    return invalidArgument(where + std::to_string(data.quality.size()) + " quality values for " + std::to_string(n) +
                           " vertices");
  }
  if (comment.find_first_of("\r\n") != std::string::npos) return invalidArgument(where + "the comment has a line break");
  if (n > std::numeric_limits<std::int32_t>::max()) return invalidArgument(where + "too many vertices for PLY's int indices");

  std::string header = "ply\nformat binary_little_endian 1.0\n";
  if (!comment.empty()) header += "comment " + comment + "\n";
  header += "element vertex " + std::to_string(n) + "\nproperty float x\nproperty float y\nproperty float z\n";
  if (!data.colours.empty()) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (!data.quality.empty()) header += "property float quality\n";
  header += "element face " + std::to_string(faces.faceCount()) + "\nproperty list uchar int vertex_indices\nend_header\n";

  std::string bytes = std::move(header);
  bytes.reserve(bytes.size() + n * 19 + faces.indices.size() * 4 + faces.faceCount());
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < n; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double x = positions[i][axis];
      if (!(std::abs(x) <= kFloatMax)) {
        return invalidArgument(where + "vertex " + std::to_string(i) + ": " + messageNumber(x) +
                               " is not a finite float32 coordinate");
      }
      appendLittleEndianF32(bytes, static_cast<float>(x));
    }
    if (!data.colours.empty()) {
      for (const std::uint8_t c : data.colours[i]) bytes.push_back(static_cast<char>(c));
    }
    if (!data.quality.empty()) appendLittleEndianF32(bytes, data.quality[i]);
  }
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f], end = faces.face_offsets[f + 1];
    if (end - begin < 3 || end - begin > 255) {
      return invalidArgument(where + "face " + std::to_string(f) + " has " + std::to_string(end - begin) +
                             " corners (PLY here takes 3 to 255)");
    }
    bytes.push_back(static_cast<char>(end - begin));
    for (std::uint32_t k = begin; k < end; ++k) {
      if (faces.indices[k] >= n) {
        return invalidArgument(where + "face " + std::to_string(f) + " names vertex " + std::to_string(faces.indices[k]) +
                               " of " + std::to_string(n));
      }
      appendLittleEndianU32(bytes, faces.indices[k]);
    }
  }
  return writeFileAtomically(path, bytes);
}

}  // namespace odeskin
