// SPDX-License-Identifier: MIT
// What every instance of one fitted asset shares, built once at load (issue 6 point 1, "load an
// asset once"): the float32 packed deformer (gpu_layout.h) per material preset, each preset's time
// bases, the bones' C1 key paths, and the triangle corners normals are recomputed from. Runtimes
// (CpuRuntime, host/runtime's VulkanRuntime) read it; it never changes after create().
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../core/result.hpp"
#include "../offline/deform_asset.hpp"
#include "../offline/deform_player.hpp"
#include "hard_edges.hpp"
#include "instance_tangents.hpp"
#include "runtime_layout.hpp"

namespace odeskin {

// A named set of materials an instance may play with instead of the asset's own (thesis 6.5.1:
// the same keys played statically or with skin dynamics). Changing materials changes the time
// bases and the rates carried across segment joins, so each preset gets its own of both.
struct MaterialPreset {
  std::string name;                 // non-empty, unique; "asset" names preset 0, the asset's own
  std::vector<Material> materials;  // one entry (used for every material of the asset) or one per material
};

// rho = eta = 0 (gamma_n = tau: the thesis's static deformation) and the thesis's skin values.
MaterialPreset staticPreset();
MaterialPreset skinPreset();

// `asset` with its materials replaced by `preset`'s and its rates re-chained (chainSegmentRates):
// the double-precision reference of an instance playing that preset. kInvalidArgument naming the
// preset when its material count fits neither rule; DeformPlayer::create's errors (a resonant mode).
Result<DeformAsset> assetWithPreset(const DeformAsset& asset, const MaterialPreset& preset);

struct RuntimeAssetOptions {
  std::vector<MaterialPreset> presets;  // become presets 1, 2, ... after the asset's own
  // gpu_layout.h influence layout: 0 keeps sparse rows; 4 or 8 fixed slots (kInvalidArgument from
  // packDeformAsset when a vertex has more influences).
  std::uint32_t influence_layout = ODESKIN_INFLUENCES_SPARSE;
  // Bind tangents for normal mapping, one per render vertex (renderVertexCount(): a glTF's vertices
  // in file order, primitives in order, as its TANGENT accessors hold them; an OBJ asset's
  // vertices): xyz, and w the handedness (+1 or -1). Empty: the asset has no tangents. Runtimes
  // created with RuntimeOptions::tangents carry them through every frame (instance_tangents.hpp).
  std::vector<gpu::Float4> render_tangents;
  // Bind normals, one per render vertex as for render_tangents (a glTF's NORMAL), xyz non-zero.
  // Empty: the asset's own (RenderLayout::normals: an asset fitted from a glTF with NORMAL keeps
  // them), if any. They only mark hard edges (hard_edges.hpp): copies of a vertex whose normals
  // differ then each take the normal of their own triangles, so creases stay creased.
  std::vector<gpu::Float4> render_normals;
};

class RuntimeAsset {
 public:
  // Validates and packs `asset` (copied; the caller's may go), builds every preset, the
  // tangents' weights and the hard edges' corners. Errors (render tangents and normals:
  // buildTangentLayout's and buildRenderCorners', naming the entry):
  // validateDeformAsset's and packDeformAsset's (kInvalidArgument), kInvalidArgument for an empty,
  // duplicate or reserved preset name or a bad material count, kOutOfRange for an asset without
  // segments or with more than 2^32 / 16 floats of data, DeformPlayer::create's for a bad material.
  static Result<RuntimeAsset> create(const DeformAsset& asset, const RuntimeAssetOptions& options = {});
  // loadAsset(path) (.odsk; kIoError / kParseError naming the path), then create().
  static Result<RuntimeAsset> load(const std::filesystem::path& path, const RuntimeAssetOptions& options = {});

  std::uint32_t vertexCount() const { return packed_[0].vertex_count; }
  std::uint32_t boneCount() const { return packed_[0].bone_count; }
  std::uint32_t segmentCount() const { return packed_[0].segment_count; }
  std::uint32_t presetCount() const { return static_cast<std::uint32_t>(packed_.size()); }
  // Time basis entries per instance and frame: material_count x (N+1) + 1 (gpu_layout.h).
  std::uint32_t basisEntries() const { return basis_entries_; }
  // Global time runs over [0, segmentCount()] in key units; one unit lasts segmentSeconds() when
  // played in real time (DeformAsset::segment_seconds).
  double endTime() const { return static_cast<double>(segmentCount()); }
  double segmentSeconds() const { return asset_.segment_seconds; }

  // Index of the preset named `name`; kInvalidArgument listing the names when there is none.
  Result<std::uint32_t> presetIndex(std::string_view name) const;
  // Empty for a preset past presetCount().
  const std::string& presetName(std::uint32_t preset) const {
    static const std::string kNone;
    return preset < preset_names_.size() ? preset_names_[preset] : kNone;
  }

  // The packed deformer of `preset` (< presetCount()): every array equals preset 0's except rates.
  const PackedDeformData& packed(std::uint32_t preset = 0) const { return packed_[preset]; }
  // The double-precision asset as given (the reference for preset 0).
  const DeformAsset& source() const { return asset_; }

  // Global time t in [0, endTime()] -> (segment, tau), as DeformPlayer::locate.
  std::pair<std::uint32_t, double> locate(double t) const { return players_[0].locate(t); }
  // Time basis of `preset` at tau (float64, then rounded): basisEntries() values into `out`.
  void basisAt(std::uint32_t preset, double tau, std::span<gpu::ModeBasis> out) const;
  // Bone matrices of `segment` at tau from the key poses' C1 paths: boneCount() values into `out`.
  void bonesAt(std::uint32_t segment, double tau, std::span<gpu::BoneMatrix> out) const;
  // Preset `preset`'s offset into the concatenation of every preset's non-empty rates (what the GPU
  // binds), or gpu::kNoRates when its rates are all zero.
  std::uint32_t ratesOffset(std::uint32_t preset) const { return rates_offsets_[preset]; }

  // Normals: vertex i's triangles as corners [cornerOffsets()[i], cornerOffsets()[i+1]) of corners()
  // (runtime_layout.h's Corner; polygons are split into fans first).
  std::span<const std::uint32_t> cornerOffsets() const { return corner_offsets_; }
  std::span<const gpu::Corner> corners() const { return corners_; }
  // Triangle list (3 indices per triangle, the same fans) for drawing the output as a mesh.
  std::span<const std::uint32_t> triangleIndices() const { return triangles_; }

  // A glTF asset's render vertices (DeformAsset::render: the input's vertices, split at UV and
  // normal seams, primitives in file order): render vertex r is topology vertex renderTopology()[r].
  // The runtime outputs them with RuntimeOptions::render_layout. Without a render layout (OBJ
  // input) they are the topology vertices: renderTopology() is empty, the count and triangles are
  // vertexCount() and triangleIndices().
  std::uint32_t renderVertexCount() const;
  // One draw per glTF primitive of the input (RenderPrimitive): a run of renderTriangleIndices()
  // and the input's material, so an engine binds each primitive's material and draws
  // [first_index, first_index + index_count) over the one output buffer. One range with material
  // -1 when the asset records no primitives; primitives without triangles are left out.
  struct DrawRange {
    std::uint32_t first_index = 0;
    std::uint32_t index_count = 0;
    std::int32_t material = -1;
  };
  std::span<const DrawRange> renderDrawRanges() const { return draw_ranges_; }
  std::span<const std::uint32_t> renderTopology() const { return asset_.render.topology_of_render; }
  std::span<const std::uint32_t> renderTriangleIndices() const {
    return asset_.render.empty() ? std::span<const std::uint32_t>(triangles_) : render_triangles_;
  }

  // RuntimeAssetOptions::render_tangents as instance_tangents.comp reads them: per render vertex
  // its handedness and the weights of its topology vertex's corner edges. Empty without tangents.
  bool hasTangents() const { return !tangents_.frames.empty(); }
  std::span<const gpu::TangentFrame> tangentFrames() const { return tangents_.frames; }
  std::span<const gpu::TangentWeights> tangentWeights() const { return tangents_.weights; }
  // With RuntimeAssetOptions::render_normals that mark hard edges: per render vertex the corners
  // its normal sums (over topology vertices); the runtime's render layout then computes normals
  // per render vertex instead of gathering the welded ones. Empty spans without hard edges.
  bool hasHardEdges() const { return render_corners_.has_value(); }
  std::uint32_t hardEdgeVertices() const { return render_corners_ ? render_corners_->hard_vertices : 0; }
  std::span<const std::uint32_t> renderCornerOffsets() const {
    return render_corners_ ? std::span<const std::uint32_t>(render_corners_->offsets) : std::span<const std::uint32_t>();
  }
  std::span<const gpu::Corner> renderCorners() const {
    return render_corners_ ? std::span<const gpu::Corner>(render_corners_->corners) : std::span<const gpu::Corner>();
  }

  // Everything computeVertexTangents reads besides one instance's positions and normals.
  TangentTables tangentTables() const {
    return {corner_offsets_, corners_, renderTopology(), tangents_.frames, tangents_.weights};
  }

 private:
  RuntimeAsset() = default;

  DeformAsset asset_;
  std::vector<std::string> preset_names_;
  std::vector<PackedDeformData> packed_;        // one per preset
  std::vector<DeformPlayer> players_;           // one per preset: its time bases
  std::vector<std::uint32_t> rates_offsets_;    // one per preset
  std::vector<RigidKeyPath> bone_paths_;        // B
  std::uint32_t basis_entries_ = 0;
  std::vector<std::uint32_t> triangles_;
  std::vector<std::uint32_t> render_triangles_;  // fans of the render faces; empty without a render layout
  std::vector<DrawRange> draw_ranges_;
  std::vector<std::uint32_t> corner_offsets_;   // V + 1
  std::vector<gpu::Corner> corners_;            // 3 per triangle
  TangentLayout tangents_;                       // per render vertex, when render_tangents were given
  std::optional<RenderCorners> render_corners_;  // when render_normals mark hard edges
};

}  // namespace odeskin
