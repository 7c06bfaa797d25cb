// SPDX-License-Identifier: MIT
// One glTF mesh as render vertices (internal to odeskin_gltf): every primitive's POSITION, NORMAL,
// TEXCOORD_0, JOINTS_n / WEIGHTS_n and morph-target POSITION deltas, primitives concatenated in file order,
// triangles (indexed or not) re-indexed into the concatenation. A primitive whose attributes and
// morph targets name the same accessors as an earlier one's shares that one's render vertices.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "gltf_accessor.hpp"

namespace odeskin::gltf {

struct MeshData {
  std::vector<Vec3> positions;                   // R render vertices (mesh space = bind space)
  std::vector<std::uint32_t> triangles;          // 3 per triangle, over render vertices
  std::size_t influence_sets = 0;                // n of the JOINTS_n / WEIGHTS_n pairs, equal in every primitive
  std::vector<std::uint32_t> joints;             // R x (4 influence_sets): skin joint indices, as stored
  std::vector<double> weights;                   // R x (4 influence_sets): decoded, not yet normalised
  std::vector<std::vector<Vec3>> target_deltas;  // T x R morph-target POSITION deltas (zeros if absent)
  std::vector<Vec3> normals;                     // R NORMAL, as stored, when every primitive has it; else empty
  // R TEXCOORD_0, decoded, when every primitive has it as float or normalized integers; else
  // empty, and `uv_warning` says why when some primitive has TEXCOORD_0 that could not be kept.
  std::vector<Vec2> uvs;
  std::string uv_warning;
  std::vector<RenderPrimitive> primitives;       // every primitive's triangle run and material
};

// Reads mesh `mesh_index`. `quantized`: the file uses KHR_mesh_quantization, so POSITION and its
// deltas may be (normalized) byte or short. kParseError naming the mesh, primitive and accessor: no
// primitives, a mode other than TRIANGLES (4), no POSITION, an index count not a multiple of 3 or
// an index >= the primitive's vertex count, JOINTS_n without WEIGHTS_n (or the reverse) or sets
// that differ between primitives, primitives with different morph-target counts, a material that
// does not exist, any readAccessor
// error, or more decoded values (accessors, unindexed triangles, zero deltas) than `budget` has left.
Result<MeshData> readMesh(const tinygltf::Model& model, int mesh_index, bool quantized, DecodeBudget& budget);

}  // namespace odeskin::gltf
