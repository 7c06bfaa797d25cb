// SPDX-License-Identifier: MIT
// Linear blend skinning, out_i = sum_b w_ib M_b X_i (thesis Eq 6.1), or dual-quaternion skinning
// (Kavan et al. 2008) by pc.skinning (skinning.glsl). Mirrors engine/kernels/lbs_job.cpp
// (reference) and LbsFastJob in fourier_deform_fast_job.cpp (float).
// Same bindings and push constants as fourier_deform.comp; only the skinning ones are declared.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "gpu_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

layout(std430, set = 0, binding = ODESKIN_BINDING_REST_POSITIONS) readonly buffer RestPositions { Float4 rest_positions[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_INFLUENCE_OFFSETS) readonly buffer InfluenceOffsets { uint influence_offsets[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_INFLUENCES) readonly buffer Influences { Influence influences[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_BONES) readonly buffer Bones { BoneMatrix bones[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_OUT_POSITIONS) writeonly buffer OutPositions { Float4 out_positions[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_BONE_DUAL_QUATS) readonly buffer BoneDualQuats { DualQuat bone_dual_quats[]; };

layout(push_constant) uniform Push { DeformPushConstants pc; };

#include "skinning.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertex_count) return;
  vec3 p = skinPoint(0u, i, vec3(rest_positions[i].x, rest_positions[i].y, rest_positions[i].z));
  out_positions[i] = Float4(p.x, p.y, p.z, 1.0);
}
