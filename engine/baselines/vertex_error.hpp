// SPDX-License-Identifier: MIT
// Error of a deformed mesh against its ground truth (MATH.md 6; thesis 6.5.2):
//   Lbox = longest side of the ground truth's axis-aligned bounding box (longestBoxSide),
//   MVE = max_i |x_i - y_i| / Lbox,   MeanVE = (1/V) sum_i |x_i - y_i| / Lbox.
#pragma once

#include <cstddef>
#include <span>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

struct VertexError {
  double mve = 0.0;               // maximum vertex error / Lbox
  double mean = 0.0;              // mean vertex error / Lbox
  std::size_t worst_vertex = 0;   // index where the maximum occurs (the first one on ties)
  double box_side = 0.0;          // Lbox of the ground truth, in its own units
};

// `deformed` and `truth`: V positions each, vertex i corresponding to vertex i (same topology and
// order); accumulated in double. Errors: kInvalidArgument for a size mismatch, an empty mesh, or a
// non-finite position (naming the side and the vertex); kDegenerate when Lbox = 0 (all ground-truth
// vertices coincide).
Result<VertexError> vertexError(std::span<const Vec3> deformed, std::span<const Vec3> truth);

}  // namespace odeskin
