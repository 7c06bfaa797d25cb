// SPDX-License-Identifier: MIT
// Tangents for normal mapping (RuntimeOptions::tangents): the engine's bind tangents (a glTF's
// TANGENT, or its own MikkTSpace) carried through each frame's deformation. CPU reference of
// shaders/instance_tangents.comp (same float operations, same order).
//
// Why carried, not recomputed from UVs: a normal map is baked against the asset's own tangents,
// and no per-frame rule reproduces an arbitrary generator's (MikkTSpace welds and splits by its
// own rules). Carried how: around each vertex the deformation is, to first order, a linear map F
// of the bind tangent plane; the least-squares F that takes the one-ring's bind edges to its
// deformed edges is linear in the deformed edges, so F t is a fixed weighted sum of them, the
// weights computed once from the bind mesh. F t is then made orthogonal to the output vertex's
// recomputed normal (across a hard edge, its own side's) and normalised. A rigid motion of the one-ring turns the tangent with it; at the bind
// pose the tangent is the bind tangent, less its component along the normal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "runtime_layout.hpp"

namespace odeskin {

// The tables instance_tangents.comp reads besides positions and normals, for O output vertices.
struct TangentLayout {
  std::vector<gpu::TangentFrame> frames;     // O
  std::vector<gpu::TangentWeights> weights;  // frame o's: one per corner of its topology vertex
};

// Views of what every frame's tangents read (RuntimeAsset's tables).
struct TangentTables {
  std::span<const std::uint32_t> corner_offsets;  // V + 1 (RuntimeAsset::cornerOffsets)
  std::span<const gpu::Corner> corners;           // RuntimeAsset::corners
  std::span<const std::uint32_t> topology;        // O: output vertex -> topology vertex; empty: the identity
  std::span<const gpu::TangentFrame> frames;      // O
  std::span<const gpu::TangentWeights> weights;
};

// Weights of every output vertex's bind tangent. `tangents`: one per output vertex (xyz any
// length, w the handedness, +1 or -1 as in glTF); `topology`: output vertex -> topology vertex,
// empty when they are the topology's vertices. A vertex whose one-ring spans no plane (no
// triangle, or degenerate ones), or a zero tangent, gets zero weights and a zero tangent every
// frame. kInvalidArgument naming the vertex for a count that is not the output vertices', a
// non-finite entry, or a w that is not +1 or -1; kOutOfRange past 32-bit weight indices.
Result<TangentLayout> buildTangentLayout(std::span<const Vec3> rest_positions, std::span<const std::uint32_t> corner_offsets,
                                         std::span<const gpu::Corner> corners, std::span<const std::uint32_t> topology,
                                         std::span<const gpu::Float4> tangents);

// Tangents of output vertices [begin, end) of one instance: `positions` are the instance's
// topology vertices (V), `normals` its output vertices' normals and `out` its tangents (O each;
// xyz unit or zero, w the handedness).
void computeVertexTangents(const TangentTables& tables, std::span<const gpu::Float4> positions,
                           std::span<const gpu::Float4> normals, std::span<gpu::Float4> out, std::size_t begin,
                           std::size_t end);

}  // namespace odeskin
