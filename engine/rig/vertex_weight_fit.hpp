// SPDX-License-Identifier: MIT
// Internal to rig/: SSDR's weight step (Le & Deng 2012, section 3.1) for fixed bone transforms:
// per vertex, the non-negative weights summing to 1 over a few candidate bones that best reproduce
// the vertex in every pose, pulled gently towards a smooth prior so that weights the poses do not
// determine (bones moving alike near that vertex) stay smooth.
#pragma once

#include <vector>

#include "rigid_clusters.hpp"
#include "weight_rows.hpp"

namespace odeskin {

// `transforms`: K x B. `prior`: V rows (sum 1, >= 0); its bones are the candidates of each vertex
// (at most 8, the largest). `prior_pull` > 0 scales the pull towards the prior relative to the
// candidates' mean squared error (1: as strong as a typical bone's misfit). Rows of the result have
// at most max_influences entries, are >= 0 and sum to 1.
std::vector<WeightRow> fitVertexWeights(const MotionData& motion, const std::vector<std::vector<RigidTransform>>& transforms,
                                        const std::vector<WeightRow>& prior, int max_influences, double prior_pull);

}  // namespace odeskin
