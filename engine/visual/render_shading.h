// SPDX-License-Identifier: MIT
// What the offscreen renderer's shaders compute, read by both C++ (engine/visual, host/render,
// tests) and GLSL (shaders/surface_*.{vert,frag}, shaders/curve_*.{vert,frag}, via #include), so
// the C++ functions below are the CPU reference of every rendered colour. Written in the subset both
// languages understand (niagara's config.h habit): GLM supplies vec3/vec4/mat4, dot, max, clamp and
// mix on the C++ side; float literals carry an f suffix; functions are marked ODESKIN_SHADER_FN.
//
// Lighting happens in view space (camera at the origin looking down -z, +y up, +x right), so a
// turntable keeps its light fixed to the camera, as a photographer's lights stay with the camera.
#ifndef ODESKIN_VISUAL_RENDER_SHADING_H
#define ODESKIN_VISUAL_RENDER_SHADING_H

#ifdef __cplusplus
#include <cstdint>

#include <glm/glm.hpp>
namespace odeskin::visual::shader {
using glm::clamp;
using glm::dot;
using glm::max;
using glm::mix;
using glm::normalize;
using mat4 = glm::mat4;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uint = std::uint32_t;
#define ODESKIN_SHADER_FN inline
#else
#define ODESKIN_SHADER_FN
#endif

// Vertex input locations of the surface pipeline (one interleaved SurfaceVertex per vertex).
#define ODESKIN_SURFACE_POSITION 0  // vec3, view space
#define ODESKIN_SURFACE_NORMAL 1    // vec3, view space, unit length
#define ODESKIN_SURFACE_VALUE 2     // float: the heat value (error), read in ODESKIN_SHADE_HEAT only

// Vertex input locations of the curve pipeline: every segment a -> b is a screen-space quad of two
// triangles, six CurveVertex records (see curveQuadCorner below).
#define ODESKIN_CURVE_POSITION 0  // vec3: this end of the segment, view space
#define ODESKIN_CURVE_OTHER 1     // vec3: the other end, view space
#define ODESKIN_CURVE_SIDE 2      // float: +1 or -1, which side of the centre line
#define ODESKIN_CURVE_COLOUR 3    // vec3: linear RGB in [0, 1]

// RenderPushConstants::shade_mode.
#define ODESKIN_SHADE_BASE 0u  // every fragment starts from base_colour
#define ODESKIN_SHADE_HEAT 1u  // fragments start from heatColour(value / heat_max)

// Two directional lights and a hemisphere ambient, as a product photo: a key light from the upper
// left in front, a weaker fill from the right. Directions point towards the lights (unnormalised
// here, normalised where used). The weights keep shadeIntensity() below 1 for every normal, so
// lighting scales a colour without clipping it, and a heat colour keeps its hue.
#define ODESKIN_KEY_LIGHT_X (-0.45f)
#define ODESKIN_KEY_LIGHT_Y 0.60f
#define ODESKIN_KEY_LIGHT_Z 0.66f
#define ODESKIN_FILL_LIGHT_X 0.70f
#define ODESKIN_FILL_LIGHT_Y 0.10f
#define ODESKIN_FILL_LIGHT_Z 0.70f
#define ODESKIN_AMBIENT 0.28f
#define ODESKIN_KEY_WEIGHT 0.60f
#define ODESKIN_FILL_WEIGHT 0.22f

// Per-draw constants (std430 push constant block: a mat4, a vec4, then 4-byte scalars; the C++
// side checks offsets in render_shading.hpp). 112 bytes, under the 128 every device offers.
struct RenderPushConstants {
  mat4 projection;          // clip from view space (Vulkan: y down, depth 0 at near, 1 at far)
  vec4 base_colour;         // rgb in [0, 1]: surface colour in ODESKIN_SHADE_BASE; a unused
  float heat_max;           // > 0: the value drawn as the top of the colour map
  uint shade_mode;          // ODESKIN_SHADE_BASE or ODESKIN_SHADE_HEAT
  float line_half_width;    // curves: half the line width, pixels
  float line_depth_offset;  // curves: view-space distance each end moves towards the camera
  float viewport_width;     // pixels
  float viewport_height;    // pixels
  float reserved0;
  float reserved1;
};

// Lambert diffuse of the two lights plus a hemisphere ambient (brighter for normals facing up):
// I(n) = A (0.8 + 0.2 n_y) + k_key max(n . l_key, 0) + k_fill max(n . l_fill, 0), for a unit
// view-space normal n that faces the viewer (back faces are drawn with their normal flipped).
ODESKIN_SHADER_FN float shadeIntensity(vec3 n) {
  vec3 key = normalize(vec3(ODESKIN_KEY_LIGHT_X, ODESKIN_KEY_LIGHT_Y, ODESKIN_KEY_LIGHT_Z));
  vec3 fill = normalize(vec3(ODESKIN_FILL_LIGHT_X, ODESKIN_FILL_LIGHT_Y, ODESKIN_FILL_LIGHT_Z));
  return ODESKIN_AMBIENT * (0.8f + 0.2f * n.y) + ODESKIN_KEY_WEIGHT * max(dot(n, key), 0.0f) +
         ODESKIN_FILL_WEIGHT * max(dot(n, fill), 0.0f);
}

// The lit colour of a surface of colour `base` with unit normal n, each channel in [0, 1].
ODESKIN_SHADER_FN vec3 shadeColour(vec3 n, vec3 base) {
  return clamp(base * shadeIntensity(n), vec3(0.0f), vec3(1.0f));
}

// The error colour map: blue (no error) -> cyan -> green -> yellow -> red (s >= 1), piecewise
// linear between five stops (the rainbow of the thesis's Fig. 6.15, toned down). Hue falls
// monotonically from about 227 to 2 degrees as s rises, which is what the heat-map tests check.
ODESKIN_SHADER_FN vec3 heatColour(float s) {
  vec3 c0 = vec3(0.17f, 0.30f, 0.80f);
  vec3 c1 = vec3(0.16f, 0.68f, 0.90f);
  vec3 c2 = vec3(0.40f, 0.80f, 0.36f);
  vec3 c3 = vec3(0.98f, 0.80f, 0.18f);
  vec3 c4 = vec3(0.86f, 0.16f, 0.13f);
  float x = clamp(s, 0.0f, 1.0f) * 4.0f;
  if (x < 1.0f) return mix(c0, c1, x);
  if (x < 2.0f) return mix(c1, c2, x - 1.0f);
  if (x < 3.0f) return mix(c2, c3, x - 2.0f);
  return mix(c3, c4, x - 3.0f);
}

// The starting colour of a surface fragment: the heat colour of value / heat_max, or base.
ODESKIN_SHADER_FN vec3 surfaceColour(uint shade_mode, vec3 base, float value, float heat_max) {
  if (shade_mode == ODESKIN_SHADE_HEAT) return heatColour(value / heat_max);
  return base;
}

#ifdef __cplusplus
}  // namespace odeskin::visual::shader
#endif

#endif  // ODESKIN_VISUAL_RENDER_SHADING_H
