// SPDX-License-Identifier: MIT
// The memory rate a compute shader reaches on this device (bench/harness/device_bandwidth.hpp):
// vec4 loads from one storage buffer and stores to another, grid-stride, through the same load and
// store units as the deformation shaders. A GPU's vkCmdCopyBuffer may run on a copy engine that is
// far slower (an H200: 846 GB/s against 4.25 TB/s), so that copy alone makes a poor yardstick. No CPU
// kernel mirrors this shader: it is the harness's ruler, not part of the deformation.
#version 450

layout(local_size_x = 256) in;

layout(std430, set = 0, binding = 0) readonly buffer Source { vec4 source[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Target { vec4 target[]; };

layout(push_constant) uniform Push {
  uint count;   // vec4s to copy
  uint stride;  // invocations in the dispatch
} pc;

void main() {
  for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += pc.stride) target[i] = source[i];
}
