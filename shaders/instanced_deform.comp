// SPDX-License-Identifier: MIT
// Every instance of one asset in one dispatch (issue 6 point 1): workgroup (x, y) deforms vertices
// [64 x, 64 x + 64) of instance y with that instance's segment, time basis, bones and material
// preset (thesis Eq 6.30 corrected, MATH.md 5.6, via deform_vertex.glsl), writes them at
// y * V + i of one output buffer, and folds them into instance y's bounding box.
// Reference: the CPU runtime backend, engine/runtime/cpu_runtime.cpp, which runs
// FourierDeformFastJob per instance (this shader's order of operations) and computeBounds
// (engine/runtime/instance_outputs.cpp) on the result.
// Bounds: subgroupMin/subgroupMax of the positions, then one atomicMin per coordinate and
// subgroup on order-preserving uint keys of the floats (runtime_layout.h), so the box is exactly
// the min and max of the written positions, whatever order the workgroups run in. Devices without
// subgroup arithmetic in compute get instanced_deform_shared.comp (a shared-memory tree: slower on
// lavapipe, where barriers are costly). The body is instanced_deform.glsl.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#define ODESKIN_BOUNDS_SUBGROUP
#include "instanced_deform.glsl"
