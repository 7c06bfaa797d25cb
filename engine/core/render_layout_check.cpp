// SPDX-License-Identifier: MIT
#include "render_layout_check.hpp"

#include "finite_vector.hpp"
#include "render_primitives.hpp"
#include "smoothing_groups.hpp"

namespace odeskin {

Status checkFaceList(const FaceList& faces, std::size_t vertex_count, const std::string& context, const std::string& what) {
  const std::vector<std::uint32_t>& offsets = faces.face_offsets;
  if (offsets.empty() || offsets.front() != 0 || offsets.back() != faces.indices.size()) {
    return invalidArgument(context + ": the " + what + " rows do not span the " + std::to_string(faces.indices.size()) +
                           " " + what + " indices");
  }
  for (std::size_t f = 0; f + 1 < offsets.size(); ++f) {
    if (offsets[f + 1] < offsets[f]) return invalidArgument(context + ": " + what + " " + std::to_string(f) + " ends before it starts");
  }
  for (std::uint32_t index : faces.indices) {
    if (index >= vertex_count) {
      return invalidArgument(context + ": a " + what + " uses vertex " + std::to_string(index) + " of " +
                             std::to_string(vertex_count));
    }
  }
  return okStatus();
}

Status checkRenderLayout(const RenderLayout& render, std::size_t topology_vertices, std::size_t topology_faces,
                         const std::string& context) {
  const std::size_t render_vertices = render.topology_of_render.size();
  for (std::uint32_t t : render.topology_of_render) {
    if (t >= topology_vertices) return invalidArgument(context + ": render vertex maps to topology vertex " + std::to_string(t));
  }
  if (render.obj_order && render.empty()) return invalidArgument(context + ": an OBJ render layout without render vertices");
  ODESKIN_TRY(checkFaceList(render.faces, render_vertices, context, "render face"));
  if (!render.normals.empty()) {
    if (render.normals.size() != render_vertices) {
      return invalidArgument(context + ": " + std::to_string(render.normals.size()) + " render normals for " +
                             std::to_string(render_vertices) + " render vertices");
    }
    for (std::size_t r = 0; r < render.normals.size(); ++r) {
      if (!isUsableNormal(render.normals[r])) {
        return invalidArgument(context + ": render normal " + std::to_string(r) + " is zero or not finite");
      }
    }
  }
  const std::size_t output_faces = render.empty() ? topology_faces : render.faces.faceCount();
  if (const std::string problem = primitiveRunProblem(render.primitives, output_faces); !problem.empty()) {
    return invalidArgument(context + ": " + problem);
  }
  if (!render.uvs.empty()) {
    const std::size_t output_vertices = render.empty() ? topology_vertices : render_vertices;
    if (render.uvs.size() != output_vertices) {
      return invalidArgument(context + ": " + std::to_string(render.uvs.size()) + " render UVs for " +
                             std::to_string(output_vertices) + " output vertices");
    }
    for (std::size_t r = 0; r < render.uvs.size(); ++r) {
      if (!isFinite(render.uvs[r])) {
        return invalidArgument(context + ": render UV " + std::to_string(r) + " is not finite");
      }
    }
  }
  return okStatus();
}

}  // namespace odeskin
