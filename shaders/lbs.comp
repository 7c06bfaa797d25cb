// SPDX-License-Identifier: MIT
// Linear blend skinning, out_i = sum_b w_ib M_b X_i (thesis Eq 6.1). Mirrors
// engine/kernels/lbs_job.cpp (reference) and lbs_fast_job in fourier_deform_fast_job.cpp (float).
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

layout(push_constant) uniform Push { DeformPushConstants pc; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertex_count) return;
  uint begin;
  uint end;
  if (pc.influence_layout == ODESKIN_INFLUENCES_SPARSE) {
    begin = influence_offsets[i];
    end = influence_offsets[i + 1u];
  } else {
    begin = i * pc.influence_layout;
    end = begin + pc.influence_layout;
  }
  vec4 h = vec4(rest_positions[i].x, rest_positions[i].y, rest_positions[i].z, 1.0);
  vec3 p = vec3(0.0);
  for (uint k = begin; k < end; ++k) {
    Influence inf = influences[k];
    BoneMatrix m = bones[inf.bone];
    vec3 q = vec3(dot(vec4(m.row0.x, m.row0.y, m.row0.z, m.row0.w), h),
                  dot(vec4(m.row1.x, m.row1.y, m.row1.z, m.row1.w), h),
                  dot(vec4(m.row2.x, m.row2.y, m.row2.z, m.row2.w), h));
    p += inf.weight * q;
  }
  out_positions[i] = Float4(p.x, p.y, p.z, 1.0);
}
