// SPDX-License-Identifier: MIT
// Analytic skin deformation of every vertex (thesis Eq 6.30 corrected, MATH.md 5.6; PIPELINE.md 3).
// Mirrors engine/kernels/fourier_deform_job.cpp (reference, double) and, operation for operation,
// engine/kernels/fourier_deform_fast_job.cpp (float):
//   D_i = (1 - w) S_a(v) + w S_b(v),  S_c(v) = sum_m (gamma_n d_cm + psi_n rdot_cm) phi_m(v)
//   bind:  out = sum_b w_b M_b (X + r^s + D + gamma_0 eps);  posed: out = LBS(X) + r^s + D + gamma_0 eps
// with LBS or dual-quaternion skinning (Kavan et al. 2008) by pc.skinning (skinning.glsl).
// Time bases are float64 host values per (material, mode) (MATH.md 1.6); the GPU only sums.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "gpu_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

layout(std430, set = 0, binding = ODESKIN_BINDING_REST_POSITIONS) readonly buffer RestPositions { Float4 rest_positions[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_VERTEX_BINDINGS) readonly buffer Bindings { VertexBinding bindings[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_SEGMENT_VERTICES) readonly buffer SegmentVertices { SegmentVertex segment_vertices[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_REMAINDERS) readonly buffer Remainders { Float4 remainders[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_CURVE_MATERIALS) readonly buffer CurveMaterials { uint curve_materials[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_COEFFICIENTS) readonly buffer Coefficients { Float4 coefficients[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_RATES) readonly buffer Rates { Float4 rates[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_INFLUENCE_OFFSETS) readonly buffer InfluenceOffsets { uint influence_offsets[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_INFLUENCES) readonly buffer Influences { Influence influences[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_BONES) readonly buffer Bones { BoneMatrix bones[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_MODE_BASIS) readonly buffer Basis { ModeBasis basis[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_OUT_POSITIONS) writeonly buffer OutPositions { Float4 out_positions[]; };
layout(std430, set = 0, binding = ODESKIN_BINDING_BONE_DUAL_QUATS) readonly buffer BoneDualQuats { DualQuat bone_dual_quats[]; };

layout(push_constant) uniform Push { DeformPushConstants pc; };

#include "skinning.glsl"

const float kTwoPi = 6.28318530717958647692;

vec3 xyz(Float4 f) { return vec3(f.x, f.y, f.z); }

// Series of curve `curve` at (cos 2 pi v, sin 2 pi v) = (c1, s1): higher harmonics by the
// angle-addition recurrence, which costs two products per mode instead of a cos and a sin.
vec3 curveSeries(uint curve, float v, float c1, float s1) {
  uint m_count = 2u * pc.modes + 2u;
  uint base = (pc.segment * pc.curve_count + curve) * m_count;
  uint basis_base = curve_materials[curve] * (pc.modes + 1u);
  ModeBasis b0 = basis[basis_base];
  vec3 d0 = xyz(coefficients[base]) + v * xyz(coefficients[base + m_count - 1u]);
  vec3 sum = b0.gamma * d0;
  if (pc.use_rates != 0u) {
    sum += b0.psi * (xyz(rates[base]) + v * xyz(rates[base + m_count - 1u]));
  }
  float cn = c1;
  float sn = s1;
  for (uint n = 1u; n <= pc.modes; ++n) {
    ModeBasis bn = basis[basis_base + n];
    vec3 dc = xyz(coefficients[base + 2u * n - 1u]);
    vec3 ds = xyz(coefficients[base + 2u * n]);
    vec3 term = cn * dc + sn * ds;
    sum += bn.gamma * term;
    if (pc.use_rates != 0u) {
      sum += bn.psi * (cn * xyz(rates[base + 2u * n - 1u]) + sn * xyz(rates[base + 2u * n]));
    }
    float c_next = cn * c1 - sn * s1;
    sn = sn * c1 + cn * s1;
    cn = c_next;
  }
  return sum;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertex_count) return;

  VertexBinding vb = bindings[i];
  float angle = kTwoPi * vb.v;
  float c1 = cos(angle);
  float s1 = sin(angle);
  vec3 series_a = curveSeries(vb.curve_a, vb.v, c1, s1);
  vec3 series_b = (vb.curve_b == vb.curve_a) ? series_a : curveSeries(vb.curve_b, vb.v, c1, s1);
  vec3 residual = (1.0 - vb.w) * series_a + vb.w * series_b;

  SegmentVertex sv = segment_vertices[pc.segment * pc.vertex_count + i];
  residual += vec3(sv.base_x, sv.base_y, sv.base_z);
  if (sv.remainder_index != ODESKIN_NO_REMAINDER) {
    float weight = basis[pc.material_count * (pc.modes + 1u)].gamma;  // the remainder weight (gpu_layout.h)
    residual += weight * xyz(remainders[pc.remainder_base + sv.remainder_index]);
  }

  vec3 rest = xyz(rest_positions[i]);
  vec3 p;
  if (pc.residual_space == ODESKIN_RESIDUAL_BIND) {
    p = skinPoint(i, rest + residual);
  } else {
    p = skinPoint(i, rest) + residual;
  }
  out_positions[i] = Float4(p.x, p.y, p.z, 1.0);
}
