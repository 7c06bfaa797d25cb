// SPDX-License-Identifier: MIT
#include "blend_error.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace odeskin {

Result<RelativeError> relativeError(std::span<const Vec3> original, std::span<const Vec3> approximation) {
  if (original.size() != approximation.size()) {
    return invalidArgument("relative error: " + std::to_string(original.size()) + " original points but " +
                           std::to_string(approximation.size()) + " approximate points");
  }
  if (original.empty()) return invalidArgument("relative error: no points");
  double largest = 0.0;
  for (std::size_t i = 0; i < original.size(); ++i) {
    for (const Vec3* p : {&original[i], &approximation[i]}) {
      if (!std::isfinite(p->x) || !std::isfinite(p->y) || !std::isfinite(p->z)) {
        return invalidArgument("relative error: point " + std::to_string(i) + " is not finite");
      }
    }
    largest = std::max(largest, glm::length(original[i]));
  }
  if (largest == 0.0) return invalidArgument("relative error: every original point is at the origin (Eq 3.44 undefined)");
  RelativeError e;
  double sum = 0.0;
  for (std::size_t i = 0; i < original.size(); ++i) {
    const double norm = glm::length(original[i]);
    if (norm < 1e-12 * largest) {
      ++e.skipped;
      continue;
    }
    const double r = glm::length(original[i] - approximation[i]) / norm;
    sum += r;
    e.max = std::max(e.max, r);
    ++e.used;
  }
  e.mean = sum / static_cast<double>(e.used);
  return e;
}

Result<BlendApproximationError> blendApproximationError(const BlendingSurface& original,
                                                        const BlendingSurface& approximation, double v_profile,
                                                        std::uint32_t profile_samples, std::uint32_t grid_samples) {
  if (!std::isfinite(v_profile)) return invalidArgument("blend error: v_profile is not finite");
  if (profile_samples < 2) return outOfRange("blend error: profile_samples must be at least 2");
  std::vector<Vec3> a(profile_samples), b(profile_samples);
  for (std::uint32_t i = 0; i < profile_samples; ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(profile_samples - 1);
    a[i] = original.at(u, v_profile);
    b[i] = approximation.at(u, v_profile);
  }
  BlendApproximationError out;
  ODESKIN_ASSIGN_OR_RETURN(out.profile, relativeError(a, b));
  ODESKIN_ASSIGN_OR_RETURN(const BlendGrid ga, tessellateBlend(original, grid_samples, grid_samples));
  ODESKIN_ASSIGN_OR_RETURN(const BlendGrid gb, tessellateBlend(approximation, grid_samples, grid_samples));
  ODESKIN_ASSIGN_OR_RETURN(out.surface, relativeError(ga.positions, gb.positions));
  return out;
}

}  // namespace odeskin
