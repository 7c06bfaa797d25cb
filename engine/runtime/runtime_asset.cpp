// SPDX-License-Identifier: MIT
#include "runtime_asset.hpp"

#include <limits>

#include "../core/render_primitives.hpp"
#include "../io/asset_file.hpp"
#include "../offline/residual_fit.hpp"
#include "instance_outputs.hpp"

namespace odeskin {
namespace {

constexpr std::string_view kAssetPresetName = "asset";

// Every index the shaders compute must fit a 32-bit uint.
Status checkIndexRange(const PackedDeformData& p, std::size_t preset_count) {
  constexpr std::size_t kMax = std::numeric_limits<std::uint32_t>::max();
  if (p.segment_vertices.size() > kMax || p.coefficients.size() * preset_count > kMax || p.remainders.size() > kMax) {
    return outOfRange("runtime asset: " + std::to_string(p.coefficients.size() * preset_count) +
                      " rates or " + std::to_string(p.segment_vertices.size()) +
                      " segment vertices exceed 32-bit indices");
  }
  return okStatus();
}

// The primitives as runs of the faces' fan triangles (renderTriangleIndices' order).
std::vector<RuntimeAsset::DrawRange> drawRanges(const FaceList& faces, std::span<const RenderPrimitive> primitives) {
  std::vector<RuntimeAsset::DrawRange> out;
  std::uint32_t index = 0;
  std::size_t f = 0;
  for (const RenderPrimitive& run : primitiveRuns(primitives, faces.faceCount())) {
    const std::uint32_t first = index;
    for (; f < run.face_end; ++f) {
      const std::uint32_t corners = faces.face_offsets[f + 1] - faces.face_offsets[f];
      if (corners >= 3) index += 3 * (corners - 2);
    }
    if (index > first) out.push_back({first, index - first, run.material});
  }
  return out;
}

}  // namespace

MaterialPreset staticPreset() { return MaterialPreset{"static", {staticMaterial()}}; }
MaterialPreset skinPreset() { return MaterialPreset{"skin", {skinMaterial()}}; }

Result<DeformAsset> assetWithPreset(const DeformAsset& asset, const MaterialPreset& preset) {
  if (preset.materials.size() != 1 && preset.materials.size() != asset.materials.size()) {
    return invalidArgument("material preset '" + preset.name + "': " + std::to_string(preset.materials.size()) +
                           " materials, expected 1 or the asset's " + std::to_string(asset.materials.size()));
  }
  DeformAsset out = asset;
  for (std::size_t m = 0; m < out.materials.size(); ++m) {
    out.materials[m] = preset.materials.size() == 1 ? preset.materials[0] : preset.materials[m];
  }
  Status chained = chainSegmentRates(out);
  if (!chained.ok()) return Status(chained.code(), "material preset '" + preset.name + "': " + chained.message());
  return out;
}

Result<RuntimeAsset> RuntimeAsset::create(const DeformAsset& asset, const RuntimeAssetOptions& options) {
  ODESKIN_TRY(validateDeformAsset(asset));
  if (asset.segments.empty()) return outOfRange("runtime asset: the asset has no segment (fewer than 2 key poses)");
  RuntimeAsset r;
  r.asset_ = asset;
  r.preset_names_.emplace_back(kAssetPresetName);
  for (const MaterialPreset& preset : options.presets) {
    if (preset.name.empty()) return invalidArgument("runtime asset: a material preset has an empty name");
    for (const std::string& name : r.preset_names_) {
      if (name == preset.name) {
        return invalidArgument("runtime asset: material preset name '" + preset.name + "' is " +
                               (name == kAssetPresetName ? "reserved for the asset's own materials" : "used twice"));
      }
    }
    r.preset_names_.push_back(preset.name);
  }

  // Preset 0 plays the asset as fitted; each other preset plays a copy with its materials.
  for (std::size_t p = 0; p < r.preset_names_.size(); ++p) {
    DeformAsset variant;
    if (p > 0) {
      ODESKIN_ASSIGN_OR_RETURN(variant, assetWithPreset(asset, options.presets[p - 1]));
    }
    const DeformAsset& played = p == 0 ? asset : variant;
    ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(played));
    ODESKIN_ASSIGN_OR_RETURN(PackedDeformData packed, packDeformAsset(played, options.influence_layout));
    r.players_.push_back(std::move(player));
    r.packed_.push_back(std::move(packed));
  }
  ODESKIN_TRY(checkIndexRange(r.packed_[0], r.packed_.size()));
  if (asset.render.topology_of_render.size() > std::numeric_limits<std::uint32_t>::max()) {
    return outOfRange("runtime asset: " + std::to_string(asset.render.topology_of_render.size()) +
                      " render vertices exceed 32-bit indices");
  }
  std::uint32_t rates = 0;
  for (const PackedDeformData& p : r.packed_) {
    r.rates_offsets_.push_back(p.rates.empty() ? gpu::kNoRates : rates);
    rates += static_cast<std::uint32_t>(p.rates.size());
  }
  r.basis_entries_ = static_cast<std::uint32_t>(r.players_[0].basisSize());
  r.bone_paths_ = boneKeyPaths(asset);
  buildCorners(asset.faces, asset.vertexCount(), r.triangles_, r.corner_offsets_, r.corners_);
  appendFanTriangles(asset.render.faces, r.render_triangles_);
  r.draw_ranges_ = drawRanges(outputFaces(asset), asset.render.primitives);
  if (!options.render_tangents.empty()) {
    ODESKIN_ASSIGN_OR_RETURN(r.tangents_, buildTangentLayout(asset.rest_positions, r.corner_offsets_, r.corners_,
                                                             asset.render.topology_of_render, options.render_tangents));
  }
  // The engine's bind normals, else the asset's own (a fit of a glTF with NORMAL keeps them).
  std::vector<Vec3> engine_normals;
  engine_normals.reserve(options.render_normals.size());
  for (const gpu::Float4& n : options.render_normals) engine_normals.emplace_back(n.x, n.y, n.z);
  const std::span<const Vec3> normals = options.render_normals.empty() ? std::span<const Vec3>(asset.render.normals)
                                                                        : std::span<const Vec3>(engine_normals);
  if (!normals.empty()) {
    ODESKIN_ASSIGN_OR_RETURN(r.render_corners_,
                             buildRenderCorners(asset.render.topology_of_render, asset.vertexCount(), r.render_triangles_,
                                                r.corner_offsets_, r.corners_, normals));
  }
  return r;
}

std::uint32_t RuntimeAsset::renderVertexCount() const {
  return static_cast<std::uint32_t>(outputVertexCount(asset_));
}

Result<RuntimeAsset> RuntimeAsset::load(const std::filesystem::path& path, const RuntimeAssetOptions& options) {
  ODESKIN_ASSIGN_OR_RETURN(DeformAsset asset, loadAsset(path));
  Result<RuntimeAsset> r = create(asset, options);
  if (!r.ok()) return Status(r.status().code(), path.string() + ": " + r.status().message());
  return r;
}

Result<std::uint32_t> RuntimeAsset::presetIndex(std::string_view name) const {
  std::string known;
  for (std::size_t p = 0; p < preset_names_.size(); ++p) {
    if (preset_names_[p] == name) return static_cast<std::uint32_t>(p);
    known += (p ? ", " : "") + preset_names_[p];
  }
  return invalidArgument("runtime asset: no material preset '" + std::string(name) + "' (presets: " + known + ")");
}

void RuntimeAsset::basisAt(std::uint32_t preset, double tau, std::span<gpu::ModeBasis> out) const {
  const DeformPlayer& player = players_[preset];
  for (std::size_t k = 0; k < out.size() && k < basis_entries_; ++k) {
    // One mode at a time: no scratch array, the same float64 values DeformPlayer::basisAt gives.
    if (k + 1 == basis_entries_) {
      out[k] = gpu::ModeBasis{static_cast<float>(remainderWeight(tau)), 0.0f};
      continue;
    }
    const std::uint32_t modes = packed_[preset].modes + 1;
    const TimeBasisSample s = player.basis(static_cast<std::uint32_t>(k / modes), static_cast<int>(k % modes)).at(tau);
    out[k] = gpu::ModeBasis{static_cast<float>(s.gamma), static_cast<float>(s.psi)};
  }
}

void RuntimeAsset::bonesAt(std::uint32_t segment, double tau, std::span<gpu::BoneMatrix> out) const {
  for (std::size_t b = 0; b < out.size() && b < bone_paths_.size(); ++b) {
    out[b] = toGpuBone(bone_paths_[b].at(segment, tau).matrix());
  }
}

}  // namespace odeskin
