// SPDX-License-Identifier: MIT
// Per-vertex error of a mesh against a reference with the same vertices, as the thesis reports it
// (Fig. 6.15, Table 6.2): distance over the reference's bounding-box diagonal.
#pragma once

#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin::visual {

// e_i = |p_i - r_i| / diag(bbox(r)). kInvalidArgument when the counts differ (both named) or the
// reference is empty or has no extent.
Result<std::vector<double>> relativeVertexErrors(std::span<const Vec3> positions, std::span<const Vec3> reference);

}  // namespace odeskin::visual
