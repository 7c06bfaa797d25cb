// SPDX-License-Identifier: MIT
// Surface pass, vertex stage: view-space positions to Vulkan clip space with the camera's
// projection; mirrors Camera::projection / projectToPixel in engine/visual/camera.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/visual/render_shading.h"

layout(location = ODESKIN_SURFACE_POSITION) in vec3 in_position;
layout(location = ODESKIN_SURFACE_NORMAL) in vec3 in_normal;
layout(location = ODESKIN_SURFACE_VALUE) in float in_value;

layout(push_constant) uniform Push { RenderPushConstants pc; };

layout(location = 0) out vec3 out_normal;
layout(location = 1) out float out_value;

void main() {
  gl_Position = pc.projection * vec4(in_position, 1.0);
  out_normal = in_normal;
  out_value = in_value;
}
