// SPDX-License-Identifier: MIT
// libFuzzer target: the OBJ reader (engine/io/obj_reader.hpp) on arbitrary bytes.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "engine/core/render_layout_check.hpp"
#include "engine/io/obj_reader.hpp"
#include "fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace odeskin;
  const std::string source = "fuzz.obj";
  const Result<ObjMesh> mesh = parseObj(fuzz::text(data, size), source);
  if (!fuzz::accepted(mesh, source)) return 0;
  // Accepted: a face list whose every corner is a vertex, faces of 3 or more corners.
  const FaceList& faces = mesh->faces;
  fuzz::require(!mesh->positions.empty() && faces.faceCount() > 0, "accepted a mesh without vertices or faces");
  fuzz::require(faces.face_offsets.front() == 0 && faces.face_offsets.back() == faces.indices.size(),
                "face offsets do not span the indices");
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    fuzz::require(faces.face_offsets[f + 1] >= faces.face_offsets[f] + 3, "accepted a face with fewer than 3 corners");
  }
  for (std::uint32_t v : faces.indices) fuzz::require(v < mesh->positions.size(), "accepted a face index out of range");
  // Kept texture coordinates and normals: one per corner, each in range; the layout built from them
  // passes the checks every asset's layout passes.
  for (const auto& [corners, count] : {std::pair{&mesh->corner_texcoords, mesh->texcoords.size()},
                                       std::pair{&mesh->corner_normals, mesh->normals.size()}}) {
    fuzz::require(corners->empty() || corners->size() == faces.indices.size(), "kept corners that are not every corner");
    fuzz::require(corners->empty() == (count == 0), "kept attributes without corners, or corners without attributes");
    for (std::uint32_t k : *corners) fuzz::require(k < count, "accepted a vt/vn index out of range");
  }
  const RenderLayout layout = objRenderLayout(*mesh);
  fuzz::require(checkRenderLayout(layout, mesh->positions.size(), faces.faceCount(), source).ok(),
                "built a render layout that fails checkRenderLayout");
  return 0;
}
