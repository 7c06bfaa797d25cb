// SPDX-License-Identifier: MIT
// Curve pass, vertex stage: each segment a -> b arrives as six vertices (two triangles) and is
// widened here to a screen-space band line_half_width pixels either side of its centre line, with
// square caps half a width long so consecutive segments of a curve join without gaps. Both ends
// first move line_depth_offset towards the camera so a curve lying on the surface wins the depth
// test against it, while the far side of the mesh still hides it.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/visual/render_shading.h"

layout(location = ODESKIN_CURVE_POSITION) in vec3 in_position;
layout(location = ODESKIN_CURVE_OTHER) in vec3 in_other;
layout(location = ODESKIN_CURVE_SIDE) in float in_side;
layout(location = ODESKIN_CURVE_COLOUR) in vec3 in_colour;

layout(push_constant) uniform Push { RenderPushConstants pc; };

layout(location = 0) out vec3 out_colour;

vec3 towardCamera(vec3 p) {
  float d = length(p);
  return d > 0.0 ? p - p * (pc.line_depth_offset / d) : p;
}

void main() {
  vec4 here = pc.projection * vec4(towardCamera(in_position), 1.0);
  vec4 there = pc.projection * vec4(towardCamera(in_other), 1.0);
  vec2 viewport = vec2(pc.viewport_width, pc.viewport_height);
  vec2 along = (there.xy / there.w - here.xy / here.w) * viewport;
  along = dot(along, along) > 1e-12 ? normalize(along) : vec2(1.0, 0.0);
  vec2 across = vec2(-along.y, along.x);
  // Pixels to NDC: 2 / viewport; to clip space: times w.
  vec2 offset_px = pc.line_half_width * (in_side * across - along);
  here.xy += offset_px * 2.0 / viewport * here.w;
  gl_Position = here;
  out_colour = in_colour;
}
