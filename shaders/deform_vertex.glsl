// SPDX-License-Identifier: MIT
// The analytic skin deformation of one vertex (thesis Eq 6.30 corrected, MATH.md 5.6; PIPELINE.md
// 3), shared by fourier_deform.comp (one mesh) and instanced_deform.comp (many instances):
//   D_i = (1 - w) S_a(v) + w S_b(v),  S_c(v) = sum_m (gamma_n d_cm + psi_n rdot_cm) phi_m(v)
//   bind:  out = skin(X + r^s + D + w(tau) eps);  posed: out = skin(X) + r^s + D + w(tau) eps
// Mirrors curveSeries / deformRange in engine/kernels/fourier_deform_fast_job.cpp operation for
// operation; the fold of the time basis into each curve's coefficients (fold_series.comp) has run
// before, in the same command buffer. The including shader declares pc (modes, material_count,
// vertex_count, residual_space and skinning.glsl's fields) and includes deform_inputs.glsl and
// skinning.glsl first.

// Where one deformation's frame values sit in the shared buffers.
struct DeformSource {
  uint segment;         // s: selects segment_vertices[s*V..]
  uint remainder_base;  // first remainder of segment s in remainders[]
  uint folded_base;     // first of this deformation's folded coefficients (fold_series.comp)
  uint basis_base;      // first ModeBasis of this deformation's time basis (the remainders' weight)
  uint bone_base;       // first bone of this deformation's palette
};

const float kTwoPi = 6.28318530717958647692;

// Series of curve `curve` at (cos 2 pi v, sin 2 pi v) = (c1, s1) from its coefficients folded with
// the frame's time basis: higher harmonics by the angle-addition recurrence, which costs two
// products per mode instead of a cos and a sin.
vec3 curveSeries(DeformSource src, uint curve, float v, float c1, float s1) {
  uint m_count = 2u * pc.modes + 2u;
  uint base = src.folded_base + curve * m_count;
  vec3 sum = foldedCoefficient(base) + v * foldedCoefficient(base + m_count - 1u);
  float cn = c1;
  float sn = s1;
  for (uint n = 1u; n <= pc.modes; ++n) {
    sum += cn * foldedCoefficient(base + 2u * n - 1u) + sn * foldedCoefficient(base + 2u * n);
    float c_next = cn * c1 - sn * s1;
    sn = sn * c1 + cn * s1;
    cn = c_next;
  }
  return sum;
}

// Deformed position of vertex i (< pc.vertex_count).
vec3 deformVertex(DeformSource src, uint i) {
  VertexBinding vb = vertexBinding(i);
  float angle = kTwoPi * vb.v;
  float c1 = cos(angle);
  float s1 = sin(angle);
  vec3 series_a = curveSeries(src, vb.curve_a, vb.v, c1, s1);
  vec3 series_b = (vb.curve_b == vb.curve_a) ? series_a : curveSeries(src, vb.curve_b, vb.v, c1, s1);
  vec3 residual = (1.0 - vb.w) * series_a + vb.w * series_b;

  SegmentVertex sv = segmentVertex(src.segment * pc.vertex_count + i);
  residual += vec3(sv.base_x, sv.base_y, sv.base_z);
  if (sv.remainder_index != ODESKIN_NO_REMAINDER) {
    // The remainder weight follows the (material, mode) entries of the basis (gpu_layout.h).
    float weight = modeBasis(src.basis_base + pc.material_count * (pc.modes + 1u)).gamma;
    residual += weight * remainder(src.remainder_base + sv.remainder_index);
  }

  vec3 rest = restPosition(i);
  if (pc.residual_space == ODESKIN_RESIDUAL_BIND) return skinPoint(src.bone_base, i, rest + residual);
  return skinPoint(src.bone_base, i, rest) + residual;
}
