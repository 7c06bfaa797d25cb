// SPDX-License-Identifier: MIT
#include "vertex_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"

namespace odeskin::visual {
namespace {

// Everything below works on halved coordinates: halving is exact (short of subnormals), and the
// halves of finite coordinates differ by at most double's maximum, so neither the box side nor a
// difference overflows where the whole ones would (a box from -1e308 to 1e308).
double halfLongestBoxSide(std::span<const Vec3> positions) {
  Vec3 lo(std::numeric_limits<double>::infinity());
  Vec3 hi(-std::numeric_limits<double>::infinity());
  for (const Vec3& p : positions) {
    lo = glm::min(lo, 0.5 * p);
    hi = glm::max(hi, 0.5 * p);
  }
  const Vec3 size = hi - lo;
  return std::max({size.x, size.y, size.z});
}

// |v| where glm::length's sum of squares would overflow (components above about 1e154): then the
// components are divided by the largest first, as hypot does.
double length(const Vec3& v) {
  const double plain = glm::length(v);
  if (std::isfinite(plain)) return plain;
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest * glm::length(v / largest);
}

}  // namespace

Result<std::vector<double>> relativeVertexErrors(std::span<const Vec3> positions, std::span<const Vec3> reference) {
  if (positions.size() != reference.size()) {
    return invalidArgument(std::to_string(positions.size()) + " vertices but the reference has " +
                           std::to_string(reference.size()));
  }
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!isFinite(positions[i])) return invalidArgument("vertex " + std::to_string(i) + " is not finite");
    if (!isFinite(reference[i])) return invalidArgument("reference vertex " + std::to_string(i) + " is not finite");
  }
  const double half_box = halfLongestBoxSide(reference);
  if (!(half_box > 0.0)) return invalidArgument("the reference mesh has no extent (zero bounding box)");
  std::vector<double> errors(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    // Scaled by the box before it is squared: the squares of distances overflow above about 1e154
    // and underflow below 1e-154, which made the errors of a 1e200 box read "inf".
    errors[i] = length((0.5 * positions[i] - 0.5 * reference[i]) / half_box);
    if (!std::isfinite(errors[i])) {
      return outOfRange("vertex " + std::to_string(i) + " is more than " +
                        numberText(std::numeric_limits<double>::max()) + " box sides (" +
                        numberText(2.0 * half_box) + ") from the reference");
    }
  }
  return errors;
}

}  // namespace odeskin::visual
