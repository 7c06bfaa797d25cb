// SPDX-License-Identifier: MIT
// The relative error of thesis Eq 3.44 (MATH.md 2.12, 6.3): for I corresponding points p_i
// (original) and pbar_i (approximation), E = (1/I) sum_i |p_i - pbar_i| / |p_i|. Undefined where
// |p_i| = 0 and dependent on the coordinate origin; points with |p_i| < 1e-12 max_i |p_i| are
// skipped and counted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "blending_surface.hpp"

namespace odeskin {

struct RelativeError {
  double mean = 0.0;        // E of Eq 3.44 over the points used
  double max = 0.0;         // the largest single |p - pbar| / |p|
  std::size_t used = 0;     // I
  std::size_t skipped = 0;  // points with |p_i| < 1e-12 max |p|
};

// Errors: kInvalidArgument when the spans differ in size, are empty, contain a non-finite
// coordinate (named by index), or every original point is at the origin.
Result<RelativeError> relativeError(std::span<const Vec3> original, std::span<const Vec3> approximation);

// Eq 3.44 between two blends of the same boundary data: on the profile curve S(u_i, v_profile),
// u_i = i/(I-1), i < I (thesis: I = 100), and on the J x J grid u_i = i/(J-1), v_j as
// tessellateBlend places them (J = 100, I = J^2).
struct BlendApproximationError {
  RelativeError profile;
  RelativeError surface;
};
Result<BlendApproximationError> blendApproximationError(const BlendingSurface& original,
                                                        const BlendingSurface& approximation, double v_profile = 0.0,
                                                        std::uint32_t profile_samples = 100,
                                                        std::uint32_t grid_samples = 100);

}  // namespace odeskin
