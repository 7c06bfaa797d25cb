// SPDX-License-Identifier: MIT
// A glTF asset's render vertices (split at UV and normal seams) from the deformed topology
// vertices, after instance_normals.comp: instance k's render vertex r copies topology vertex
// topology[r]'s position and normal, so an engine binds the outputs beside the glTF's own UVs
// (RuntimeOptions::render_layout). Plain copies: the CPU runtime's gather (gatherRenderVertices in
// engine/runtime/instance_outputs.cpp) gives the same bits.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/runtime/runtime_layout.h"

layout(local_size_x = ODESKIN_WORKGROUP_SIZE) in;

layout(std430, set = 0, binding = ODESKIN_RT_GATHER_BINDING_POSITIONS) readonly buffer Positions { vec4 positions[]; };
layout(std430, set = 0, binding = ODESKIN_RT_GATHER_BINDING_NORMALS) readonly buffer Normals { vec4 normals[]; };
layout(std430, set = 0, binding = ODESKIN_RT_GATHER_BINDING_TOPOLOGY) readonly buffer Topology { uint topology[]; };
layout(std430, set = 0, binding = ODESKIN_RT_GATHER_BINDING_OUT_POSITIONS) writeonly buffer OutPositions { vec4 out_positions[]; };
layout(std430, set = 0, binding = ODESKIN_RT_GATHER_BINDING_OUT_NORMALS) writeonly buffer OutNormals { vec4 out_normals[]; };

layout(push_constant) uniform Push { GatherPushConstants pc; };

void main() {
  uint r = gl_GlobalInvocationID.x;
  if (r >= pc.render_count) return;
  uint k = gl_WorkGroupID.y;
  uint from = k * pc.vertex_count + topology[r];
  uint to = k * pc.render_count + r;
  out_positions[to] = positions[from];
  if (pc.normals != 0u) out_normals[to] = normals[from];
}
