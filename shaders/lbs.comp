// SPDX-License-Identifier: MIT
// Linear blend skinning, out_i = sum_b w_ib M_b X_i (thesis Eq 6.1), or dual-quaternion skinning
// (Kavan et al. 2008) by pc.skinning (skinning.glsl). Mirrors engine/kernels/lbs_job.cpp
// (reference) and LbsFastJob in fourier_deform_fast_job.cpp (float).
// Same bindings and push constants as fourier_deform.comp; it reads only the skinning ones.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "gpu_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

#include "deform_inputs.glsl"
layout(std430, set = 0, binding = ODESKIN_BINDING_OUT_POSITIONS) writeonly buffer OutPositions { vec4 out_positions[]; };

layout(push_constant) uniform Push { DeformPushConstants pc; };

#include "skinning.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertex_count) return;
  vec3 p = skinPoint(0u, i, restPosition(i));
  out_positions[i] = vec4(p.x, p.y, p.z, 1.0);
}
