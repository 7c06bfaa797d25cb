// SPDX-License-Identifier: MIT
// The three-plane corner of thesis Sec. 3.5 (Eqs 3.22-3.25, MATH.md 2.13, C16, C17): a box corner
// whose top (z = z0 + lz + r), front (y = y0) and side (x = lx + r) planes are joined by three
// rounded-edge ODE blends, top-front (TF), top-side (TS) and front-side (FS), all on v in [0, 1],
// and the three-sided hole where they meet closed by a fourth ODE blend whose u = 0 trimline
// collapses to the corner point:
//   C0 = S_TF(0, 1),  C0bar = T0 + (T1 - T0) l(v)  (T0 = dS_TF/du(0, 1), T1 = dS_TS/du(0, 0),
//   l = normalised arc length of the bottom curve),  C1 = S_FS(v, 1),  C1bar = s dS_FS/dv(v, 1).
// The thesis prints s = +1; a tangent that continues smoothly into FS needs s < 0 (C17), so the
// default is s = -1. With s = -1/2 (for lz = 1: -0.5 lz / lz) the patch's v = 0 and v = 1 edges
// coincide with the TF and TS edges exactly, since the end tangents then equal theirs.
#pragma once

#include <array>

#include "../core/result.hpp"
#include "blend_examples.hpp"
#include "blending_surface.hpp"

namespace odeskin {

// Eq 3.22's dimensions (thesis values as defaults).
struct CornerDimensions {
  double y0 = 1.0;
  double z0 = 0.5;
  double lx = 1.0;
  double ly = 1.2;
  double lz = 1.0;
  double r = 0.25;  // the offset between the planes that the blends round off
};

struct CornerBlendOptions {
  CornerDimensions dimensions;
  BlendShapeParameters parameters{1.0, 2.0, 1.0};  // used by all four blends (thesis: 1, 2, 1)
  double bottom_tangent_scale = -1.0;              // s in C1bar = s dS_FS/dv (C17)
};

struct CornerBlend {
  BlendingSurface top_front;   // Eq 3.22
  BlendingSurface top_side;    // Eq 3.23 (C16 corrected)
  BlendingSurface front_side;  // Eq 3.24
  BlendingSurface patch;       // Eq 3.25, the three-sided patch
};

// Errors: kInvalidArgument naming a dimension that is not finite or (lx, ly, lz, r) not positive,
// or a non-finite bottom_tangent_scale; the errors of BlendingSurface::create for the parameters.
Result<CornerBlend> makeCornerBlend(const CornerBlendOptions& options = {});

// The three plane rectangles the blends join (top, front, side), corners counter-clockwise seen
// from outside the box, for pictures.
std::array<std::array<Vec3, 4>, 3> cornerPlaneQuads(const CornerDimensions& dimensions);

}  // namespace odeskin
