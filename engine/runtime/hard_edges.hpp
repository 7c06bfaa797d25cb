// SPDX-License-Identifier: MIT
// Hard edges of a glTF asset's render layout (RuntimeAssetOptions::render_normals). The runtime's
// normals are the welded surface's, which is right across a UV seam and wrong across a hard edge,
// where it would smooth the crease away. Given the bind normals, a vertex with more than one
// smoothing group (engine/core/smoothing_groups.hpp) is on a hard edge, and each of its groups
// takes the normal of the triangles its own copies belong to. Every other render vertex keeps its
// topology vertex's corners, so its normal is the gathered one to the bit.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "runtime_layout.hpp"

namespace odeskin {

// Per render vertex r, the corners its normal sums, over topology vertices (positions are the
// topology's): instance_normals.comp's lists in render vertices, r's own position topology[r].
struct RenderCorners {
  std::vector<std::uint32_t> offsets;  // R + 1
  std::vector<gpu::Corner> corners;
  std::uint32_t hard_vertices = 0;     // topology vertices with more than one smoothing group
};

// The render corners of a render layout with hard edges, or nothing when every topology vertex
// has one smoothing group (its normals are then exactly the gathered ones). `normals`: one per
// render vertex (topology.size(), or the topology's vertex count when `topology` is empty: no
// render layout, no hard edge), any non-zero length. `render_triangles`: 3 render
// vertices each; `corner_offsets`, `corners`: the topology's (RuntimeAsset's). kInvalidArgument
// naming the normal for a wrong count, a non-finite or a zero normal; kOutOfRange past 32-bit
// corner indices.
Result<std::optional<RenderCorners>> buildRenderCorners(std::span<const std::uint32_t> topology, std::size_t vertex_count,
                                                        std::span<const std::uint32_t> render_triangles,
                                                        std::span<const std::uint32_t> corner_offsets,
                                                        std::span<const gpu::Corner> corners,
                                                        std::span<const Vec3> normals);

}  // namespace odeskin
