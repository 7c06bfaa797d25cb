// SPDX-License-Identifier: MIT
#include "packed_deform.hpp"

#include "dual_quaternion.hpp"

namespace odeskin {

std::size_t PackedDeformData::byteSize() const {
  return rest_positions.size() * sizeof(gpu::Float4) + bindings.size() * sizeof(gpu::VertexBinding) +
         segment_vertices.size() * sizeof(gpu::SegmentVertex) + remainders.size() * sizeof(gpu::Float4) +
         curve_materials.size() * sizeof(std::uint32_t) + coefficients.size() * sizeof(gpu::Float4) +
         rates.size() * sizeof(gpu::Float4) + influence_offsets.size() * sizeof(std::uint32_t) +
         influences.size() * sizeof(gpu::Influence);
}

gpu::BoneMatrix toGpuBone(const BoneTransform& bone) {
  // GLM is column-major: bone[column][row]; the GPU reads rows.
  auto row = [&](int r) {
    return gpu::Float4{static_cast<float>(bone[0][r]), static_cast<float>(bone[1][r]),
                       static_cast<float>(bone[2][r]), static_cast<float>(bone[3][r])};
  };
  return gpu::BoneMatrix{row(0), row(1), row(2)};
}

BoneTransform fromGpuBone(const gpu::BoneMatrix& bone) {
  const gpu::Float4 rows[3] = {bone.row0, bone.row1, bone.row2};
  BoneTransform m;
  for (int r = 0; r < 3; ++r) {
    m[0][r] = rows[r].x;
    m[1][r] = rows[r].y;
    m[2][r] = rows[r].z;
    m[3][r] = rows[r].w;
  }
  return m;
}

gpu::Float4 toGpuFloat4(const Vec3& v, float w) {
  return gpu::Float4{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z), w};
}

void toGpuBones(std::span<const BoneTransform> bones, std::span<gpu::BoneMatrix> out) {
  for (std::size_t b = 0; b < bones.size() && b < out.size(); ++b) out[b] = toGpuBone(bones[b]);
}

void toGpuBasis(std::span<const ModeBasisValue> basis, std::span<gpu::ModeBasis> out) {
  for (std::size_t k = 0; k < basis.size() && k < out.size(); ++k) {
    out[k] = gpu::ModeBasis{static_cast<float>(basis[k].gamma), static_cast<float>(basis[k].psi)};
  }
}

gpu::DualQuat toGpuDualQuaternion(const gpu::BoneMatrix& bone) {
  const DualQuaternion q = DualQuaternion::fromRigid(fromGpuBone(bone));
  auto f4 = [](const glm::dquat& v) {
    return gpu::Float4{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z),
                       static_cast<float>(v.w)};
  };
  return gpu::DualQuat{f4(q.real), f4(q.dual)};
}

void toGpuDualQuaternions(std::span<const gpu::BoneMatrix> bones, std::span<gpu::DualQuat> out) {
  for (std::size_t b = 0; b < bones.size() && b < out.size(); ++b) out[b] = toGpuDualQuaternion(bones[b]);
}

gpu::DeformPushConstants deformPushConstants(const PackedDeformData& data, std::uint32_t segment) {
  gpu::DeformPushConstants pc{};
  pc.vertex_count = data.vertex_count;
  pc.modes = data.modes;
  pc.curve_count = data.curve_count;
  pc.material_count = data.material_count;
  pc.bone_count = data.bone_count;
  pc.segment = segment;
  pc.remainder_base = segment < data.remainder_base.size() ? data.remainder_base[segment] : 0;
  pc.influence_layout = data.influence_layout;
  pc.residual_space = data.residual_space == ResidualSpace::kBind ? ODESKIN_RESIDUAL_BIND : ODESKIN_RESIDUAL_POSED;
  pc.use_rates = data.rates.empty() ? 0u : 1u;
  pc.skinning = data.skinning == SkinningMode::kDualQuaternion ? ODESKIN_SKINNING_DUAL_QUATERNION
                                                                : ODESKIN_SKINNING_LINEAR;
  return pc;
}

}  // namespace odeskin
