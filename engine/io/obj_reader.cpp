// SPDX-License-Identifier: MIT
#include "obj_reader.hpp"

#include <string_view>
#include <unordered_map>

#include "../core/finite_vector.hpp"
#include "../core/smoothing_groups.hpp"
#include "text_tokens.hpp"

namespace odeskin {
namespace {

constexpr long long kNone = 0;  // a corner without a `vt` or `vn` index (OBJ indices start at 1)

// One attribute a corner may name (`vt` or `vn`): the corners' raw indices as written and the
// first reason the attribute cannot be kept. Index problems drop the attribute, not the mesh.
struct CornerAttribute {
  CornerAttribute(const char* what_name, const char* keyword_name) : what(what_name), keyword(keyword_name) {}

  const char* what;     // "texture coordinate"
  const char* keyword;  // "vt"
  std::vector<long long> raw;  // per corner: kNone, or 1-based after negative indices are resolved
  std::size_t named = 0;       // corners that name one
  std::size_t lines = 0;       // `vt`/`vn` lines read so far
  std::string problem;

  // Keeps the first problem only.
  void fail(std::string why) {
    if (problem.empty()) problem = std::move(why);
  }
  // `token`: the corner's field for this attribute (empty when the corner has none), on `line` of
  // `source`.
  void addCorner(std::string_view token, const std::string& source, std::size_t line) {
    long long index = kNone;
    if (!token.empty()) {
      ++named;
      const bool number = parseInt(token, index) && index != 0;
      if (!number) index = kNone;
      if (index < 0) index += static_cast<long long>(lines) + 1;  // counts back from the lines so far
      // Only the first problem is kept, so its text is made only while there is none: a file whose
      // every corner repeats one fault costs no more than a good one.
      if (problem.empty() && (!number || index < 1 || index > static_cast<long long>(lines))) {
        const std::string why = !number    ? std::string(" is not an index (a whole number other than 0)")
                                : index < 1 ? std::string(" points before the first `") + keyword + "`"
                                            : ", but only " + std::to_string(lines) + " `" + keyword + "` lines come before it";
        problem = source + ":" + std::to_string(line) + ": " + what + " index '" + std::string(token) + "'" + why;
      }
    }
    raw.push_back(index);
  }
  // The 0-based indices, or empty when no corner names one or the attribute is dropped. Corners
  // that name one in a file without any (the cylinder of ../shared/data writes `f 1/1 2/2 21/22`
  // and no `vt`) have nothing to keep, and nothing is lost: no warning then.
  std::vector<std::uint32_t> resolve(const std::string& source) {
    if (lines == 0) problem.clear();
    if (named > 0 && named < raw.size() && lines > 0) {
      fail(source + ": " + std::to_string(named) + " of " + std::to_string(raw.size()) + " face corners name a `" +
           keyword + "`; all or none must");
    }
    if (named == 0 && lines > 0) {
      fail(source + ": " + std::to_string(lines) + " `" + keyword + "` line" + (lines == 1 ? "" : "s") +
           ", but no face names one");
    }
    std::vector<std::uint32_t> out;
    if (!problem.empty() || named == 0 || lines == 0) return out;
    out.reserve(raw.size());
    for (long long index : raw) out.push_back(static_cast<std::uint32_t>(index - 1));
    return out;
  }
};

// "a/t/n" split at its slashes: the vertex, texture and normal fields (empty where absent).
struct CornerFields {
  std::string_view vertex, texcoord, normal;
};

CornerFields splitCorner(std::string_view token) {
  CornerFields c;
  const std::size_t first = token.find('/');
  c.vertex = token.substr(0, first);
  if (first == std::string_view::npos) return c;
  const std::string_view rest = token.substr(first + 1);
  const std::size_t second = rest.find('/');
  c.texcoord = rest.substr(0, second);
  if (second != std::string_view::npos) c.normal = rest.substr(second + 1);
  return c;
}

}  // namespace

Result<ObjMesh> readObj(const std::filesystem::path& path) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string text, readTextFile(path));
  return parseObj(text, path.string());
}

Result<ObjMesh> parseObj(const std::string& text, const std::string& source) {
  ObjMesh mesh;
  std::vector<long long> raw;  // face corners as written (1-based or negative), resolved below
  std::vector<std::size_t> face_lines;
  CornerAttribute texcoords{"texture coordinate", "vt"};
  CornerAttribute normals{"normal", "vn"};
  LineReader reader(text);
  std::string_view line;
  while (reader.next(line)) {
    const std::size_t line_number = reader.number();
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    const std::string_view keyword = nextToken(line);
    auto where = [&] { return source + ":" + std::to_string(line_number) + ": "; };
    auto error = [&](const std::string& what) { return parseError(where() + what); };
    if (keyword == "v") {
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        if (!parseDouble(nextToken(line), p[k])) return error("vertex needs 3 finite coordinates");
      }
      mesh.positions.push_back(p);  // an optional w or colour after x y z is ignored
    } else if (keyword == "vt") {
      // u [v [w]]: v defaults to 0 as the format says; a 3D texture's w is not kept.
      Vec2 uv(0.0);
      const std::string_view u_token = nextToken(line);
      const std::string_view v_token = nextToken(line);
      if (!parseDouble(u_token, uv.x) || (!v_token.empty() && !parseDouble(v_token, uv.y))) {
        texcoords.fail(where() + "`vt` needs finite coordinates");
      }
      mesh.texcoords.push_back(uv);
      ++texcoords.lines;
    } else if (keyword == "vn") {
      Vec3 n;
      for (int k = 0; k < 3; ++k) {
        if (!parseDouble(nextToken(line), n[k])) {
          normals.fail(where() + "`vn` needs 3 finite coordinates");
          break;
        }
      }
      mesh.normals.push_back(n);
      ++normals.lines;
    } else if (keyword == "f") {
      std::size_t corners = 0;
      for (std::string_view token = nextToken(line); !token.empty(); token = nextToken(line), ++corners) {
        const CornerFields fields = splitCorner(token);
        long long index = 0;
        if (!parseInt(fields.vertex, index) || index == 0) return error("bad face index '" + std::string(token) + "'");
        // Negative indices count back from the vertices read so far.
        if (index < 0) index = static_cast<long long>(mesh.positions.size()) + index + 1;
        if (index < 1) return error("face index '" + std::string(token) + "' points before the first vertex");
        raw.push_back(index - 1);
        texcoords.addCorner(fields.texcoord, source, line_number);
        normals.addCorner(fields.normal, source, line_number);
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
  mesh.corner_texcoords = texcoords.resolve(source);
  mesh.corner_normals = normals.resolve(source);
  // A named normal that is zero cannot shade; the hard edges it would mark are dropped with it.
  for (std::uint32_t n : mesh.corner_normals) {
    if (!isUsableNormal(mesh.normals[n])) {
      normals.fail(source + ": normal " + std::to_string(n + 1) + " is zero");
      mesh.corner_normals.clear();
      break;
    }
  }
  mesh.texcoord_warning = texcoords.problem;
  mesh.normal_warning = normals.problem;
  if (mesh.corner_texcoords.empty()) mesh.texcoords.clear();
  if (mesh.corner_normals.empty()) mesh.normals.clear();
  return mesh;
}

RenderLayout objRenderLayout(const ObjMesh& mesh) {
  RenderLayout layout;
  const bool uvs = !mesh.corner_texcoords.empty();
  const bool normals = !mesh.corner_normals.empty();
  if (!uvs && !normals) return layout;
  layout.obj_order = true;
  // Key: the corner's (v, vt, vn), each below 2^32; the attributes a mesh lacks count as 0.
  struct Key {
    std::uint32_t v, t, n;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::hash<std::uint64_t>()((std::uint64_t(k.v) << 32) ^ (std::uint64_t(k.t) * 0x9E3779B97F4A7C15ull) ^ k.n);
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> render_of;
  render_of.reserve(mesh.positions.size() * 2);
  layout.faces.face_offsets = mesh.faces.face_offsets;
  layout.faces.indices.reserve(mesh.faces.indices.size());
  for (std::size_t k = 0; k < mesh.faces.indices.size(); ++k) {
    const Key key{mesh.faces.indices[k], uvs ? mesh.corner_texcoords[k] : 0, normals ? mesh.corner_normals[k] : 0};
    const auto [it, added] = render_of.try_emplace(key, static_cast<std::uint32_t>(layout.topology_of_render.size()));
    if (added) {
      layout.topology_of_render.push_back(key.v);
      if (uvs) {
        const Vec2& uv = mesh.texcoords[key.t];
        layout.uvs.emplace_back(uv.x, 1.0 - uv.y);
      }
      if (normals) layout.normals.push_back(mesh.normals[key.n]);
    }
    layout.faces.indices.push_back(it->second);
  }
  return layout;
}

std::vector<std::string> objLayoutWarnings(const ObjMesh& mesh) {
  std::vector<std::string> out;
  if (!mesh.texcoord_warning.empty()) out.push_back("texture coordinates (vt) are not kept: " + mesh.texcoord_warning);
  if (!mesh.normal_warning.empty()) out.push_back("normals (vn) are not kept: " + mesh.normal_warning);
  return out;
}

}  // namespace odeskin
