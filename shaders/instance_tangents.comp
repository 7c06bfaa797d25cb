// SPDX-License-Identifier: MIT
// Tangents of every instance for normal mapping (RuntimeOptions::tangents), after
// instance_normals.comp: output vertex o (a render vertex with a render layout) of topology vertex
// i carries its bind tangent through the frame's deformation as a weighted sum of i's deformed
// corner edges (the least-squares deformation gradient of the one-ring; TangentFrame and
// TangentWeights in runtime_layout.h), made orthogonal to o's output normal and normalised; w is
// the bind handedness. A gather per output vertex, like the normals.
// Reference: computeVertexTangents in engine/runtime/instance_tangents.cpp (same float
// operations, same order), which the CPU runtime backend runs per instance.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/runtime/runtime_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_POSITIONS) readonly buffer Positions { Float4 positions[]; };
layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_NORMALS) readonly buffer Normals { Float4 normals[]; };
layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_CORNER_OFFSETS) readonly buffer CornerOffsets { uint corner_offsets[]; };
layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_CORNERS) readonly buffer Corners { Corner corners[]; };
layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_TOPOLOGY) readonly buffer Topology { uint topology[]; };
layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_FRAMES) readonly buffer Frames { TangentFrame frames[]; };
layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_WEIGHTS) readonly buffer Weights { TangentWeights weights[]; };
layout(std430, set = 0, binding = ODESKIN_RT_TANGENTS_BINDING_OUT_TANGENTS) writeonly buffer OutTangents { vec4 out_tangents[]; };

layout(push_constant) uniform Push { TangentsPushConstants pc; };

vec3 position(uint k) { return vec3(positions[k].x, positions[k].y, positions[k].z); }

void main() {
  uint o = gl_GlobalInvocationID.x;
  if (o >= pc.output_count) return;
  uint base = gl_WorkGroupID.y * pc.vertex_count;  // instance y's topology vertices
  uint i = pc.render_layout != 0u ? topology[o] : o;
  TangentFrame frame = frames[o];
  vec3 p = position(base + i);
  vec3 t = vec3(0.0);
  uint first = corner_offsets[i];
  uint end = corner_offsets[i + 1u];
  for (uint k = first; k < end; ++k) {
    Corner c = corners[k];
    TangentWeights w = weights[frame.weights + (k - first)];
    t += w.next * (position(base + c.next) - p) + w.prev * (position(base + c.prev) - p);
  }
  uint out_index = gl_WorkGroupID.y * pc.output_count + o;
  vec3 n = vec3(normals[out_index].x, normals[out_index].y, normals[out_index].z);
  t -= n * dot(n, t);
  float len = length(t);
  t = len > 0.0 ? t / len : vec3(0.0);
  out_tangents[out_index] = vec4(t.x, t.y, t.z, frame.handedness);
}
