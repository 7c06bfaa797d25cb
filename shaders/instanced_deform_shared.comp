// SPDX-License-Identifier: MIT
// instanced_deform.comp for devices without subgroup arithmetic in compute shaders: the same
// deformation (instanced_deform.glsl), the bounds folded by a min/max tree in shared memory.
// Reference: the CPU runtime backend (engine/runtime/cpu_runtime.cpp), as for instanced_deform.comp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "instanced_deform.glsl"
