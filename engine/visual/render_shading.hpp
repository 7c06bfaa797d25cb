// SPDX-License-Identifier: MIT
// C++ side of render_shading.h: the vertex records the renderer uploads and the layout checks that
// keep the push constant block identical in C++ and GLSL.
#pragma once

#include <cstddef>

#include "render_shading.h"

namespace odeskin::visual {

using shader::RenderPushConstants;

// One vertex of the surface pipeline (locations ODESKIN_SURFACE_*), 28 bytes, tightly packed.
struct SurfaceVertex {
  float position[3];  // view space
  float normal[3];    // view space, unit
  float value;        // heat value (error as a fraction of the reference's box diagonal), or 0
};

// One vertex of the curve pipeline (locations ODESKIN_CURVE_*), 40 bytes, tightly packed.
struct CurveVertex {
  float position[3];  // this end, view space
  float other[3];     // the other end, view space
  float side;         // +1 or -1
  float colour[3];    // linear RGB
};

static_assert(sizeof(SurfaceVertex) == 28 && offsetof(SurfaceVertex, value) == 24);
static_assert(sizeof(CurveVertex) == 40 && offsetof(CurveVertex, side) == 24 && offsetof(CurveVertex, colour) == 28);

// std430 offsets (GLSL): mat4 at 0, vec4 at 64, then scalars every 4 bytes.
static_assert(sizeof(glm::mat4) == 64 && sizeof(glm::vec4) == 16, "GLM must not pad its types");
static_assert(offsetof(RenderPushConstants, base_colour) == 64);
static_assert(offsetof(RenderPushConstants, heat_max) == 80);
static_assert(offsetof(RenderPushConstants, shade_mode) == 84);
static_assert(offsetof(RenderPushConstants, line_half_width) == 88);
static_assert(offsetof(RenderPushConstants, line_depth_offset) == 92);
static_assert(offsetof(RenderPushConstants, viewport_width) == 96);
static_assert(offsetof(RenderPushConstants, viewport_height) == 100);
static_assert(sizeof(RenderPushConstants) == 112 && sizeof(RenderPushConstants) <= 128);

}  // namespace odeskin::visual
