// SPDX-License-Identifier: MIT
// Vertex normals of every instance, recomputed from the deformed triangles after
// instanced_deform.comp: n_i = normalize(sum over i's corners of cross(p[next] - p[i], p[prev] - p[i])),
// the area-weighted sum of the incident triangles' normals, (0, 0, 0) where it vanishes. A gather
// per vertex (RuntimeAsset's corner lists), so no float atomics and a fixed summation order. Across
// hard edges the same over render vertices (RuntimeAsset::renderCorners), each render vertex's own
// position its topology vertex's (render_layout = 1).
// Reference: computeVertexNormals (computeRenderNormals) in engine/runtime/instance_outputs.cpp
// (same float operations, same order), which the CPU runtime backend runs per instance.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/runtime/runtime_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

// Inputs as uniform texel buffers (host/texel_bindings.hpp; deform_inputs.glsl says why).
layout(set = 0, binding = ODESKIN_RT_NORMALS_BINDING_POSITIONS) uniform samplerBuffer positions;       // Float4
layout(set = 0, binding = ODESKIN_RT_NORMALS_BINDING_CORNER_OFFSETS) uniform usamplerBuffer corner_offsets; // uint
layout(set = 0, binding = ODESKIN_RT_NORMALS_BINDING_CORNERS) uniform usamplerBuffer corners;         // Corner
layout(set = 0, binding = ODESKIN_RT_NORMALS_BINDING_TOPOLOGY) uniform usamplerBuffer topology;       // uint
layout(std430, set = 0, binding = ODESKIN_RT_NORMALS_BINDING_OUT_NORMALS) writeonly buffer OutNormals { vec4 out_normals[]; };

layout(push_constant) uniform Push { NormalsPushConstants pc; };

vec3 position(uint k) { return texelFetch(positions, int(k)).xyz; }

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertex_count) return;
  uint base = gl_WorkGroupID.y * pc.position_count;  // instance y's positions
  uint self = pc.render_layout != 0u ? texelFetch(topology, int(i)).x : i;
  vec3 p = position(base + self);
  vec3 n = vec3(0.0);
  uint end = texelFetch(corner_offsets, int(i + 1u)).x;
  for (uint k = texelFetch(corner_offsets, int(i)).x; k < end; ++k) {
    uvec2 c = texelFetch(corners, int(k)).xy;  // Corner: next, prev
    n += cross(position(base + c.x) - p, position(base + c.y) - p);
  }
  float len = length(n);
  n = len > 0.0 ? n / len : vec3(0.0);
  out_normals[gl_WorkGroupID.y * pc.vertex_count + i] = vec4(n.x, n.y, n.z, 0.0);
}
