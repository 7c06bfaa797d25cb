// SPDX-License-Identifier: MIT
// The vertex data of a glTF export in its output layout: the asset's render vertices when it came
// from glTF (as `play` writes them), else its topology vertices; triangles, smooth normals of the
// base shape (each side of the input's hard edges its own, when the asset kept the input's
// normals), and at most 4 skin influences per vertex (glTF's JOINTS_0/WEIGHTS_0, ECOSYSTEM.md 2.2).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../offline/deform_asset.hpp"

namespace odeskin {

inline constexpr std::uint32_t kExportInfluences = 4;

struct ExportMesh {
  std::vector<std::uint32_t> source_vertex;  // output vertex -> topology vertex
  std::vector<std::uint32_t> triangles;      // 3 output vertex indices each (polygons as fans)
  // The input's primitives (asset.render.primitives) as runs of `triangles`: primitive p has
  // triangles [primitive_ends[p - 1], primitive_ends[p]). One primitive when the asset records none.
  std::vector<std::uint32_t> primitive_ends;
  std::vector<Vec3> positions;               // output vertices of the base shape
  std::vector<Vec3> normals;                 // output vertices: unit, area-weighted, of the base shape
  std::vector<Vec2> uvs;                     // output vertices: the input's TEXCOORD_0, or empty
  // Output vertices x 4, largest weight first. Unused slots are (joint 0, weight 0); the weights are
  // renormalised in float32 so their float32 sum is 1 within an ulp (the validator's test).
  std::vector<std::array<std::uint32_t, kExportInfluences>> joints;
  std::vector<std::array<float, kExportInfluences>> weights;
  std::uint32_t max_influences = 0;          // most influences of one vertex in the asset
  std::uint32_t pruned_vertices = 0;         // vertices that had more than 4
  double max_prune_error = 0.0;              // max |LBS_4 - LBS_all| over the key poses (absolute)
};

// `base_positions`: V topology positions of the shape the morph targets start from (X + r^0).
// `key_bones`: the bone transforms of every key pose (each bone_count long), where the pruning
// error is measured. kInvalidArgument for sizes that disagree with the asset.
Result<ExportMesh> buildExportMesh(const DeformAsset& asset, std::span<const Vec3> base_positions,
                                   std::span<const std::vector<BoneTransform>> key_bones);

}  // namespace odeskin
