// SPDX-License-Identifier: MIT
// Analytic skin deformation of every vertex (thesis Eq 6.30 corrected, MATH.md 5.6; PIPELINE.md 3).
// Mirrors engine/kernels/fourier_deform_job.cpp (reference, double) and, operation for operation,
// engine/kernels/fourier_deform_fast_job.cpp (float):
//   D_i = (1 - w) S_a(v) + w S_b(v),  S_c(v) = sum_m (gamma_n d_cm + psi_n rdot_cm) phi_m(v)
//   bind:  out = sum_b w_b M_b (X + r^s + D + gamma_0 eps);  posed: out = LBS(X) + r^s + D + gamma_0 eps
// with LBS or dual-quaternion skinning (Kavan et al. 2008) by pc.skinning (skinning.glsl). The
// per-vertex work is deform_vertex.glsl's, shared with instanced_deform.comp.
// Time bases are float64 host values per (material, mode) (MATH.md 1.6); fold_series.comp has
// folded them into the curves' coefficients before this dispatch, so the GPU only sums.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "gpu_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

#include "deform_inputs.glsl"
layout(std430, set = 0, binding = ODESKIN_BINDING_OUT_POSITIONS) writeonly buffer OutPositions { vec4 out_positions[]; };

layout(push_constant) uniform Push { DeformPushConstants pc; };

#include "skinning.glsl"
#include "deform_vertex.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertex_count) return;
  // One mesh: the frame's segment from the push constants, the whole folded, basis and bone buffers.
  DeformSource src = DeformSource(pc.segment, pc.remainder_base, 0u, 0u, 0u);
  vec3 p = deformVertex(src, i);
  out_positions[i] = vec4(p.x, p.y, p.z, 1.0);
}
