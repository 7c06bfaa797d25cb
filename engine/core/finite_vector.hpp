// SPDX-License-Identifier: MIT
// The finiteness test every input check makes of a position, normal or texture coordinate, kept in
// one place so that a check cannot forget a component.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace odeskin {

template <glm::length_t L, typename T, glm::qualifier Q>
bool isFinite(const glm::vec<L, T, Q>& v) {
  for (glm::length_t i = 0; i < L; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace odeskin
