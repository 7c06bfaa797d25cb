// SPDX-License-Identifier: MIT
// The frame's time basis folded into every curve's coefficients (thesis Eq 6.30 corrected, MATH.md
// 5.6), once per frame and deformation instead of once per vertex:
//   A_cm = gamma_n(m) d_cm + psi_n(m) rdot_cm      (gamma_n(m) d_cm where the deformation has no rates)
// The deformation shaders' series (deform_vertex.glsl) then fetch one texel per entry instead of a
// basis entry, a coefficient and a rate, which halves their fetches (docs/performance.md).
// Invocation (x, y) folds entry x = c M + m of deformation y, whose segment and rates come from its
// InstanceRecord (the runtime's, or the one a single mesh writes per frame) and whose basis starts
// at y E, and writes it at y C M + x. Mirrors `folded` in engine/kernels/fourier_deform_fast_job.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/runtime/runtime_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

layout(set = 0, binding = ODESKIN_BINDING_CURVE_MATERIALS) uniform usamplerBuffer curve_materials;  // uint
layout(set = 0, binding = ODESKIN_BINDING_COEFFICIENTS) uniform samplerBuffer coefficients;         // Float4
layout(set = 0, binding = ODESKIN_BINDING_RATES) uniform samplerBuffer rates;                       // Float4
layout(set = 0, binding = ODESKIN_BINDING_MODE_BASIS) uniform samplerBuffer basis;                  // ModeBasis
layout(set = 0, binding = ODESKIN_RT_BINDING_INSTANCES) uniform usamplerBuffer records;             // InstanceRecord
layout(std430, set = 0, binding = ODESKIN_BINDING_FOLDED_SERIES) writeonly buffer Folded { vec4 folded[]; };

layout(push_constant) uniform Push { FoldPushConstants pc; };

void main() {
  uint m_count = 2u * pc.modes + 2u;
  uint entries = pc.curve_count * m_count;
  uint x = gl_GlobalInvocationID.x;
  if (x >= entries) return;
  uint y = gl_WorkGroupID.y;
  uvec4 t = texelFetch(records, int(y));
  InstanceRecord r = InstanceRecord(t.x, t.y, t.z, t.w);
  uint curve = x / m_count;
  uint m = x - curve * m_count;
  // Entry 0 (constant) and M - 1 (open-curve trend) follow mode 0; 2n - 1 and 2n mode n.
  uint n = m == m_count - 1u ? 0u : (m + 1u) / 2u;
  uint material = texelFetch(curve_materials, int(curve)).x;
  vec2 b = texelFetch(basis, int(y * pc.basis_entries + material * (pc.modes + 1u) + n)).xy;
  uint k = r.segment * entries + x;
  vec3 d = texelFetch(coefficients, int(k)).xyz;
  vec3 a = r.rates_offset == ODESKIN_RT_NO_RATES ? b.x * d : b.x * d + b.y * texelFetch(rates, int(r.rates_offset + k)).xyz;
  folded[y * entries + x] = vec4(a.x, a.y, a.z, 0.0);
}
