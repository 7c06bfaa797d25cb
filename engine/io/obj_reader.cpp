// SPDX-License-Identifier: MIT
#include "obj_reader.hpp"

#include <string_view>

#include "text_tokens.hpp"

namespace odeskin {
namespace {

// a, a/t, a//n, a/t/n: the vertex index a.
bool parseIndex(std::string_view token, long long& out) { return parseInt(token.substr(0, token.find('/')), out); }

}  // namespace

Result<ObjMesh> readObj(const std::filesystem::path& path) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string text, readTextFile(path));
  return parseObj(text, path.string());
}

Result<ObjMesh> parseObj(const std::string& text, const std::string& source) {
  ObjMesh mesh;
  std::vector<long long> raw;  // face corners as written (1-based or negative), resolved below
  std::vector<std::size_t> face_lines;
  LineReader reader(text);
  std::string_view line;
  while (reader.next(line)) {
    const std::size_t line_number = reader.number();
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    const std::string_view keyword = nextToken(line);
    auto error = [&](const std::string& what) {
      return parseError(source + ":" + std::to_string(line_number) + ": " + what);
    };
    if (keyword == "v") {
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        if (!parseDouble(nextToken(line), p[k])) return error("vertex needs 3 finite coordinates");
      }
      mesh.positions.push_back(p);  // an optional w or colour after x y z is ignored
    } else if (keyword == "f") {
      std::size_t corners = 0;
      for (std::string_view token = nextToken(line); !token.empty(); token = nextToken(line), ++corners) {
        long long index = 0;
        if (!parseIndex(token, index) || index == 0) return error("bad face index '" + std::string(token) + "'");
        // Negative indices count back from the vertices read so far.
        if (index < 0) index = static_cast<long long>(mesh.positions.size()) + index + 1;
        if (index < 1) return error("face index '" + std::string(token) + "' points before the first vertex");
        raw.push_back(index - 1);
      }
      if (corners < 3) return error("face has " + std::to_string(corners) + " corners, needs at least 3");
      mesh.faces.face_offsets.push_back(static_cast<std::uint32_t>(raw.size()));
      face_lines.push_back(line_number);
    }
  }
  if (mesh.positions.empty()) return parseError(source + ": no vertices");
  if (mesh.faces.faceCount() == 0) return parseError(source + ": no faces");
  mesh.faces.indices.reserve(raw.size());
  for (std::size_t f = 0; f < mesh.faces.faceCount(); ++f) {
    for (std::uint32_t k = mesh.faces.face_offsets[f]; k < mesh.faces.face_offsets[f + 1]; ++k) {
      if (raw[k] >= static_cast<long long>(mesh.positions.size())) {
        return parseError(source + ":" + std::to_string(face_lines[f]) + ": face index " +
                          std::to_string(raw[k] + 1) + " > vertex count " + std::to_string(mesh.positions.size()));
      }
      mesh.faces.indices.push_back(static_cast<std::uint32_t>(raw[k]));
    }
  }
  return mesh;
}

}  // namespace odeskin
