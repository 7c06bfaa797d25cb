// SPDX-License-Identifier: MIT
// Surface pass, fragment stage: surfaceColour (base or heatColour(value / heat_max)) lit by
// shadeColour, both from engine/visual/render_shading.h, which is also their CPU reference. Back
// faces (seen through holes or from inside) are lit with the normal turned towards the viewer.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/visual/render_shading.h"

layout(push_constant) uniform Push { RenderPushConstants pc; };

layout(location = 0) in vec3 in_normal;
layout(location = 1) in float in_value;

layout(location = 0) out vec4 out_colour;

void main() {
  vec3 n = normalize(in_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 base = surfaceColour(pc.shade_mode, pc.base_colour.rgb, in_value, pc.heat_max);
  out_colour = vec4(shadeColour(n, base), 1.0);
}
