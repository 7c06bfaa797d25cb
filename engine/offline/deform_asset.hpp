// SPDX-License-Identifier: MIT
// A fitted deformer: everything needed to play the analytic skin deformation between key poses
// (PIPELINE.md 3-5), in double precision. packDeformAsset turns it into the float32 GPU layout.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "../core/iso_curve.hpp"
#include "../core/result.hpp"
#include "../core/types.hpp"
#include "../kernels/influences.hpp"
#include "../kernels/packed_deform.hpp"
#include "material.hpp"
#include "rigid_transform.hpp"

namespace odeskin {

// Segment s plays key pose s -> s+1.
struct DeformSegment {
  std::vector<Vec3> base_residuals;                // V: bind-space corrective r^s of key s
  std::vector<Vec3> coefficients;                  // C * (2N+2): d^s (target Delta^s = r^{s+1} - r^s)
  std::vector<Vec3> rates;                         // C * (2N+2): rdot^s, the rate carried into s
  std::vector<std::uint32_t> remainder_indices;    // V: index into remainders or kNoRemainder
  std::vector<Vec3> remainders;                    // sparse eps (PIPELINE.md 4), follow gamma_0
};

struct DeformAsset {
  int modes = 0;                                   // N
  ResidualSpace residual_space = ResidualSpace::kBind;
  SkinningMode skinning = SkinningMode::kLinear;
  double segment_seconds = 1.0;                    // playback length of one segment
  std::vector<Vec3> rest_positions;                // V: bind mesh X
  FaceList faces;
  RenderLayout render;                             // glTF input: the render vertices (empty for OBJ)
  std::vector<CurveBinding> bindings;              // V
  std::vector<IsoCurve> curves;                    // C on the bind mesh (display, refits); may be empty
  std::vector<std::uint32_t> curve_materials;      // C
  std::vector<Material> materials;                 // >= 1
  Influences influences;                           // V rows
  std::uint32_t bone_count = 0;                    // B
  std::vector<Vec3> bone_pivots;                   // B: joint of each bone in bind space
  std::vector<std::int32_t> bone_parents;          // B (-1: root), or empty
  std::vector<std::string> bone_names;             // B, or empty
  std::vector<std::vector<RigidTransform>> key_poses;  // K x B
  std::vector<DeformSegment> segments;             // K - 1

  std::size_t vertexCount() const { return rest_positions.size(); }
  std::size_t curveCount() const { return curve_materials.size(); }
};

// Positions in the asset's output layout: the render vertices (topology positions gathered through
// topology_of_render) when the asset has a render layout, else the topology positions themselves.
std::vector<Vec3> outputPositions(const DeformAsset& asset, std::span<const Vec3> topology_positions);
// The faces of that layout, and its vertex count.
const FaceList& outputFaces(const DeformAsset& asset);
std::size_t outputVertexCount(const DeformAsset& asset);
// The vertices OBJ frames and point caches hold: the topology vertices, in the input's order, when
// the render layout came from an OBJ (RenderLayout::obj_order: the frames' corners name their UVs),
// else the output layout's. A point cache thus fits the mesh `play --t 0 -o BASE.obj` writes.
std::vector<Vec3> objPositions(const DeformAsset& asset, std::span<const Vec3> topology_positions);
std::size_t objVertexCount(const DeformAsset& asset);
// Unit vertex normals of the shape `topology_positions` (V) in that layout: the area-weighted
// normals of the welded topology (polygon fans), so UV seams do not show, except across the
// input's hard edges (RenderLayout::normals, engine/core/smoothing_groups.hpp), where each side
// takes its own faces'. (0, 0, 1) where a vertex has no direction (degenerate faces only): glTF
// still requires a unit normal there.
std::vector<Vec3> outputNormals(const DeformAsset& asset, std::span<const Vec3> topology_positions);

// Checks every size and index of `asset` (kInvalidArgument naming the field and element).
Status validateDeformAsset(const DeformAsset& asset);

// Float32 GPU layout (gpu_layout.h). influence_layout: 0 keeps every influence in sparse rows; 4 or
// 8 requests fixed slots (kInvalidArgument if a vertex has more; prune first). kInvalidArgument
// naming the field and element for a position, residual, remainder, coefficient or rate beyond
// 1e38 (kFloat32CoordinateLimit: float32 would hold infinities); validateDeformAsset's errors.
Result<PackedDeformData> packDeformAsset(const DeformAsset& asset, std::uint32_t influence_layout = 0);

}  // namespace odeskin
