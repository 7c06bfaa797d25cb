// SPDX-License-Identifier: MIT
// Body of instanced_deform.comp (subgroup reduction of the bounds) and instanced_deform_shared.comp
// (shared-memory reduction, for devices without subgroup arithmetic in compute): the same deformation,
// two ways to fold a workgroup's positions into the instance's box. The including .comp declares
// #version, the extensions (GL_GOOGLE_include_directive, and the subgroup ones with
// ODESKIN_BOUNDS_SUBGROUP defined when it reduces by subgroups).
#include "../engine/runtime/runtime_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

#include "deform_inputs.glsl"
layout(std430, set = 0, binding = ODESKIN_RT_BINDING_OUT_POSITIONS) writeonly buffer OutPositions { vec4 out_positions[]; };
ODESKIN_INPUT(ODESKIN_RT_BINDING_INSTANCES, Instances, uvec4, instances)  // InstanceRecord
layout(std430, set = 0, binding = ODESKIN_RT_BINDING_BOUNDS) buffer Bounds { uint bounds[]; };  // BoundsKeys[instances], 8 uints each

layout(push_constant) uniform Push { InstancedPushConstants pc; };

#include "skinning.glsl"
#include "deform_vertex.glsl"

#ifndef ODESKIN_BOUNDS_SUBGROUP
shared vec3 lo_shared[ODESKIN_WORKGROUP_SIZE];
shared vec3 hi_shared[ODESKIN_WORKGROUP_SIZE];
#endif

// gpu::orderedKey in runtime_layout.hpp: unsigned order of keys = float order of values.
uint orderedKey(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint instance = gl_WorkGroupID.y;
  uint lane = gl_LocalInvocationID.x;

  // Lanes past the last vertex take part in the reduction with an empty box.
  vec3 lo = vec3(uintBitsToFloat(0x7F800000u));  // +inf
  vec3 hi = -lo;
  if (i < pc.vertex_count) {
    uvec4 t = uvec4(ODESKIN_FETCH(instances, instance));
    InstanceRecord r = InstanceRecord(t.x, t.y, t.z, t.w);
    // The fold pass (fold_series.comp) has folded the instance's basis into its own coefficients.
    DeformSource src = DeformSource(r.segment, r.remainder_base, instance * pc.curve_count * (2u * pc.modes + 2u),
                                    instance * pc.basis_entries, instance * pc.bone_count);
    vec3 p = deformVertex(src, i);
    out_positions[instance * pc.vertex_count + i] = vec4(p.x, p.y, p.z, 1.0);
    lo = p;
    hi = p;
  }

  // keys[0..2] hold min(x), keys[4..6] min(-x) = -max(x) (runtime_layout.h).
#ifdef ODESKIN_BOUNDS_SUBGROUP
  // One atomic per subgroup and coordinate; every lane is active here (no early return above).
  vec3 box_lo = subgroupMin(lo);
  vec3 box_hi = subgroupMax(hi);
  if (subgroupElect()) {
#else
  // A min/max tree over the workgroup in shared memory, then one atomic per coordinate.
  lo_shared[lane] = lo;
  hi_shared[lane] = hi;
  barrier();
  for (uint stride = ODESKIN_WORKGROUP_SIZE / 2u; stride > 0u; stride >>= 1u) {
    if (lane < stride) {
      lo_shared[lane] = min(lo_shared[lane], lo_shared[lane + stride]);
      hi_shared[lane] = max(hi_shared[lane], hi_shared[lane + stride]);
    }
    barrier();
  }
  vec3 box_lo = lo_shared[0];
  vec3 box_hi = hi_shared[0];
  if (lane == 0u) {
#endif
    atomicMin(bounds[instance * 8u + 0u], orderedKey(box_lo.x));
    atomicMin(bounds[instance * 8u + 1u], orderedKey(box_lo.y));
    atomicMin(bounds[instance * 8u + 2u], orderedKey(box_lo.z));
    atomicMin(bounds[instance * 8u + 4u], orderedKey(-box_hi.x));
    atomicMin(bounds[instance * 8u + 5u], orderedKey(-box_hi.y));
    atomicMin(bounds[instance * 8u + 6u], orderedKey(-box_hi.z));
  }
}
