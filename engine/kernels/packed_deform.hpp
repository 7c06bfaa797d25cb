// SPDX-License-Identifier: MIT
// The float32 layout of a deformer (gpu_layout.h): what the fast CPU path reads and what host/
// uploads to the GPU once, byte for byte. Built from a DeformAsset by packDeformAsset (offline/).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/gpu_layout.hpp"
#include "../core/types.hpp"

namespace odeskin {

struct PackedDeformData {
  std::uint32_t vertex_count = 0;    // V
  std::uint32_t modes = 0;           // N; M = 2N+2 coefficients per curve
  std::uint32_t curve_count = 0;     // C
  std::uint32_t material_count = 0;
  std::uint32_t bone_count = 0;      // B
  std::uint32_t segment_count = 0;   // S
  std::uint32_t influence_layout = ODESKIN_INFLUENCES_SPARSE;  // 0 (sparse rows), 4 or 8 (slots)
  ResidualSpace residual_space = ResidualSpace::kBind;
  // kDualQuaternion: the fast path and the GPU also need toGpuDualQuaternions of each frame's bones.
  SkinningMode skinning = SkinningMode::kLinear;

  std::vector<gpu::Float4> rest_positions;          // V
  std::vector<gpu::VertexBinding> bindings;         // V
  std::vector<gpu::SegmentVertex> segment_vertices; // S * V
  std::vector<gpu::Float4> remainders;              // all segments, segment s from remainder_base[s]
  std::vector<std::uint32_t> remainder_base;        // S
  std::vector<std::uint32_t> curve_materials;       // C
  std::vector<gpu::Float4> coefficients;            // S * C * M
  std::vector<gpu::Float4> rates;                   // S * C * M
  std::vector<std::uint32_t> influence_offsets;     // V + 1 for the sparse layout, else empty
  std::vector<gpu::Influence> influences;           // sparse: influence_offsets[V]; slots: V * layout

  std::uint32_t coefficientsPerCurve() const { return 2 * modes + 2; }
  // Bytes the GPU holds for this deformer (everything above), for reports.
  std::size_t byteSize() const;
};

gpu::BoneMatrix toGpuBone(const BoneTransform& bone);
// The float rows back as a double matrix (exact): what a reference kernel plays for bones given as
// the GPU gets them.
BoneTransform fromGpuBone(const gpu::BoneMatrix& bone);
gpu::Float4 toGpuFloat4(const Vec3& v, float w = 0.0f);
// Converts per-frame values for the fast path and the GPU.
void toGpuBones(std::span<const BoneTransform> bones, std::span<gpu::BoneMatrix> out);
void toGpuBasis(std::span<const ModeBasisValue> basis, std::span<gpu::ModeBasis> out);
// The unit dual quaternion of each bone's rigid part (DualQuaternion::fromRigid, in double, then
// rounded), for dual-quaternion skinning. Taken from the float rows the GPU gets, so the fast path
// and the shader blend exactly the same numbers.
gpu::DualQuat toGpuDualQuaternion(const gpu::BoneMatrix& bone);
void toGpuDualQuaternions(std::span<const gpu::BoneMatrix> bones, std::span<gpu::DualQuat> out);

// Push constants for segment `segment` of `data` (shared by the fast path and the dispatcher).
gpu::DeformPushConstants deformPushConstants(const PackedDeformData& data, std::uint32_t segment);

}  // namespace odeskin
