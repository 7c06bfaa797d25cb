// SPDX-License-Identifier: MIT
#include "frame_traffic.hpp"

namespace odeskin::bench {

std::size_t frameBytes(const PackedDeformData& d, std::uint32_t segment, bool deforms) {
  const std::size_t v = d.vertex_count;
  std::size_t bytes = v * sizeof(gpu::Float4) * 2;  // rest positions in, deformed positions out
  bytes += d.influences.size() * sizeof(gpu::Influence) + d.influence_offsets.size() * sizeof(std::uint32_t);
  bytes += std::size_t{d.bone_count} * sizeof(gpu::BoneMatrix);
  if (d.skinning == SkinningMode::kDualQuaternion) bytes += std::size_t{d.bone_count} * sizeof(gpu::DualQuat);
  if (!deforms) return bytes;

  bytes += v * (sizeof(gpu::VertexBinding) + sizeof(gpu::SegmentVertex));
  for (std::size_t i = 0; i < v; ++i) {
    if (d.segment_vertices[std::size_t{segment} * v + i].remainder_index != gpu::kNoRemainder) bytes += sizeof(gpu::Float4);
  }
  const std::size_t series = std::size_t{d.curve_count} * d.coefficientsPerCurve() * sizeof(gpu::Float4);
  bytes += series;
  if (deformPushConstants(d, segment).use_rates != 0) bytes += series;
  bytes += d.curve_materials.size() * sizeof(std::uint32_t);
  bytes += ODESKIN_BASIS_ENTRIES(std::size_t{d.material_count}, std::size_t{d.modes}) * sizeof(gpu::ModeBasis);
  return bytes;
}

}  // namespace odeskin::bench
