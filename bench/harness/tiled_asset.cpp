// SPDX-License-Identifier: MIT
#include "tiled_asset.hpp"

#include <string>

namespace odeskin::bench {
namespace {

template <typename T>
std::vector<T> tiled(const std::vector<T>& source, std::size_t count) {
  std::vector<T> out;
  if (source.empty()) return out;  // optional per-vertex arrays stay absent
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(source[i % source.size()]);
  return out;
}

Influences tiledInfluences(const Influences& source, std::size_t count) {
  Influences out;
  const std::size_t v = source.vertexCount();
  if (v == 0) return out;  // nothing to tile
  out.offsets.reserve(count + 1);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t s = i % v;
    for (std::uint32_t k = source.offsets[s]; k < source.offsets[s + 1]; ++k) {
      out.bones.push_back(source.bones[k]);
      out.weights.push_back(source.weights[k]);
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.bones.size()));
  }
  return out;
}

}  // namespace

Result<DeformAsset> tileDeformAsset(const DeformAsset& source, std::size_t vertex_count) {
  if (source.vertexCount() == 0) return invalidArgument("tileDeformAsset: the source asset has no vertices");
  if (vertex_count == 0) return invalidArgument("tileDeformAsset: vertex_count is 0");
  if (source.influences.vertexCount() != source.vertexCount()) {
    return invalidArgument("tileDeformAsset: the source has " + std::to_string(source.influences.vertexCount()) +
                           " influence rows for " + std::to_string(source.vertexCount()) + " vertices");
  }
  DeformAsset out;
  out.modes = source.modes;
  out.residual_space = source.residual_space;
  out.skinning = source.skinning;
  out.segment_seconds = source.segment_seconds;
  out.rest_positions = tiled(source.rest_positions, vertex_count);
  out.bindings = tiled(source.bindings, vertex_count);
  out.curve_materials = source.curve_materials;
  out.materials = source.materials;
  out.influences = tiledInfluences(source.influences, vertex_count);
  out.bone_count = source.bone_count;
  out.bone_pivots = source.bone_pivots;
  out.bone_parents = source.bone_parents;
  out.bone_names = source.bone_names;
  out.key_poses = source.key_poses;
  out.segments.reserve(source.segments.size());
  for (const DeformSegment& s : source.segments) {
    DeformSegment t;
    t.base_residuals = tiled(s.base_residuals, vertex_count);
    t.coefficients = s.coefficients;
    t.rates = s.rates;
    t.remainder_indices = tiled(s.remainder_indices, vertex_count);  // copies share the source's remainders
    t.remainders = s.remainders;
    out.segments.push_back(std::move(t));
  }
  return out;
}

}  // namespace odeskin::bench
