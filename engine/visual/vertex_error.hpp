// SPDX-License-Identifier: MIT
// Per-vertex error of a mesh against a reference with the same vertices, as the thesis reports it
// (Fig. 6.15, Table 6.2) and MATH.md 6.1 defines it: distance over Lbox, the longest side of the
// reference's axis-aligned bounding box. The same Lbox as `odeskin evaluate` and the fit's key
// tolerance, so a heat map's maximum is the Maximum Vertex Error.
#pragma once

#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin::visual {

// e_i = |p_i - r_i| / Lbox(r), exact to rounding for any finite coordinates (no overflow of the
// squares). kInvalidArgument when the counts differ (both named), a vertex is not finite (named),
// or the reference is empty or has no extent; kOutOfRange (naming the vertex) when an error is
// beyond double's range (a vertex far outside a tiny reference box).
Result<std::vector<double>> relativeVertexErrors(std::span<const Vec3> positions, std::span<const Vec3> reference);

}  // namespace odeskin::visual
