// SPDX-License-Identifier: MIT
// Comparing rigid transforms in tests: the rig, Kabsch and automatic-rig tests all ask whether a
// recovered bone transform is the expected one.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "engine/offline/rigid_transform.hpp"

namespace odeskin::testing {

// Largest entry of |R_a - R_b| and |t_a - t_b|: compared as matrices, because quaternions q and -q
// are the same rotation.
inline double transformDistance(const RigidTransform& a, const RigidTransform& b) {
  const glm::dmat3 ra = glm::mat3_cast(a.rotation);
  const glm::dmat3 rb = glm::mat3_cast(b.rotation);
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(ra[c][r] - rb[c][r]));
    worst = std::max(worst, std::abs(a.translation[c] - b.translation[c]));
  }
  return worst;
}

}  // namespace odeskin::testing
