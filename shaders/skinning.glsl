// SPDX-License-Identifier: MIT
// Skinning of one point, shared by fourier_deform.comp, lbs.comp and instanced_deform.comp: linear
// blend skinning (thesis Eq 6.1) or dual-quaternion skinning (Kavan et al. 2008, Algorithm 1),
// chosen by pc.skinning. Mirrors skinPoint / skinPointDq in
// engine/kernels/fourier_deform_fast_job.cpp operation for operation (reference:
// engine/kernels/dual_quaternion.cpp). The including shader declares pc (with influence_layout and
// skinning) and includes deform_inputs.glsl first. `bone_base`
// is the first bone of the palette in use: 0 for one mesh, instance x bone_count when instanced.

void influenceRange(uint vertex, out uint begin, out uint end) {
  if (pc.influence_layout == ODESKIN_INFLUENCES_SPARSE) {
    begin = influenceOffset(vertex);
    end = influenceOffset(vertex + 1u);
  } else {
    begin = vertex * pc.influence_layout;
    end = begin + pc.influence_layout;
  }
}

vec3 skinPointLbs(uint bone_base, uint vertex, vec3 p) {
  uint begin;
  uint end;
  influenceRange(vertex, begin, end);
  vec4 h = vec4(p, 1.0);
  vec3 out_p = vec3(0.0);
  for (uint k = begin; k < end; ++k) {
    Influence inf = influence(k);
    uint b = bone_base + inf.bone;
    vec3 q = vec3(dot(boneRow(b, 0u), h), dot(boneRow(b, 1u), h), dot(boneRow(b, 2u), h));
    out_p += inf.weight * q;
  }
  return out_p;
}

// Bones taken on the side of the first largest weight's quaternion (q and -q are one rotation),
// blended, divided by |real|, applied as x -> R x + t. A degenerate blend skins by LBS.
vec3 skinPointDq(uint bone_base, uint vertex, vec3 p) {
  uint begin;
  uint end;
  influenceRange(vertex, begin, end);
  if (begin == end) return skinPointLbs(bone_base, vertex, p);
  uint pivot = begin;
  for (uint k = begin + 1u; k < end; ++k) {
    if (influence(k).weight > influence(pivot).weight) pivot = k;
  }
  vec4 pivot_real = dualQuatReal(bone_base + influence(pivot).bone);
  vec4 real = vec4(0.0);
  vec4 dual = vec4(0.0);
  for (uint k = begin; k < end; ++k) {
    Influence inf = influence(k);
    vec4 q_real = dualQuatReal(bone_base + inf.bone);
    float w = dot(q_real, pivot_real) < 0.0 ? -inf.weight : inf.weight;
    real += w * q_real;
    dual += w * dualQuatDual(bone_base + inf.bone);
  }
  float norm = length(real);
  if (!(norm > ODESKIN_DQS_MIN_BLEND_NORM)) return skinPointLbs(bone_base, vertex, p);
  float inv_norm = 1.0 / norm;
  vec4 r = real * inv_norm;
  vec4 e = dual * inv_norm;
  vec3 t = 2.0 * (r.w * e.xyz - e.w * r.xyz + cross(r.xyz, e.xyz));
  float xx = r.x * r.x, yy = r.y * r.y, zz = r.z * r.z;
  float xy = r.x * r.y, xz = r.x * r.z, yz = r.y * r.z;
  float wx = r.w * r.x, wy = r.w * r.y, wz = r.w * r.z;
  vec3 c0 = vec3(1.0 - 2.0 * (yy + zz), 2.0 * (xy + wz), 2.0 * (xz - wy));
  vec3 c1 = vec3(2.0 * (xy - wz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz + wx));
  vec3 c2 = vec3(2.0 * (xz + wy), 2.0 * (yz - wx), 1.0 - 2.0 * (xx + yy));
  return c0 * p.x + c1 * p.y + c2 * p.z + t;
}

vec3 skinPoint(uint bone_base, uint vertex, vec3 p) {
  return pc.skinning == ODESKIN_SKINNING_DUAL_QUATERNION ? skinPointDq(bone_base, vertex, p)
                                                         : skinPointLbs(bone_base, vertex, p);
}
