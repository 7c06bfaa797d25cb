// SPDX-License-Identifier: MIT
// The checks a face list and a render layout (types.hpp) pass before anything indexes through
// them. The asset check and the glTF writers that take a layout share them, so a broken layout is
// refused in the same words wherever it comes from.
#pragma once

#include <cstddef>
#include <string>

#include "status.hpp"
#include "types.hpp"

namespace odeskin {

// Rows that span `faces.indices` in order, every index below `vertex_count`. kInvalidArgument;
// messages start with `context` and call the list's rows `what` ("face", "render face").
Status checkFaceList(const FaceList& faces, std::size_t vertex_count, const std::string& context, const std::string& what);

// `render` over a topology of `topology_vertices` vertices and `topology_faces` faces: render
// vertices map to topology vertices and render faces index render vertices; normals, if any, one
// usable normal per render vertex; UVs, if any, one finite pair per output vertex; primitive runs
// that cover the output faces. The output vertices and faces are the render ones, or the
// topology's where the layout is empty. kInvalidArgument, messages starting with `context`.
Status checkRenderLayout(const RenderLayout& render, std::size_t topology_vertices, std::size_t topology_faces,
                         const std::string& context);

}  // namespace odeskin
