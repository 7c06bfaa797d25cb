// SPDX-License-Identifier: MIT
// Skinning weights from a skeleton alone: a distance-based scheme in the spirit of Yang & Zhang
// (2006), smoothed over the mesh and normalised (see the .cpp for the exact scheme and why).
#pragma once

#include <span>

#include "../core/result.hpp"
#include "rig.hpp"

namespace odeskin {

struct DistanceWeightOptions {
  int max_influences = 4;        // per vertex, after pruning and renormalising
  double falloff_power = 4.0;    // weight ~ 1 / distance^power to the bone segment
  int smoothing_iterations = 10; // Laplacian smoothing over the mesh's vertex graph
};

// kInvalidArgument for a skeleton without bones, bad faces, positions not finite or too large
// or small for double-precision lengths (checkedPositionBox), or options out of range.
Result<Influences> distanceWeights(std::span<const Vec3> rest, const FaceList& faces, const Skeleton& skeleton,
                                   const DistanceWeightOptions& options = {});

}  // namespace odeskin
