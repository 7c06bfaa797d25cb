// SPDX-License-Identifier: MIT
// A rig derived from the example poses alone (--rig auto): vertices are clustered by consistent
// rigid motion across the poses, each cluster becomes a bone with per-pose transforms (Kabsch),
// joints are placed where neighbouring bones agree, and weights are smoothed over the mesh.
#pragma once

#include <span>
#include <vector>

#include "../core/result.hpp"
#include "rig.hpp"

namespace odeskin {

struct AutoRigOptions {
  int bones = 0;             // 0: chosen from the mesh and the motion
  int max_influences = 4;
  int iterations = 20;       // cluster / refit rounds
};

struct AutoRigReport {
  int bones = 0;
  double max_error = 0.0;    // worst vertex of LBS(rig) vs the example poses, / longest box side
  double mean_error = 0.0;   // mean vertex error, / longest box side
};

// rest: the bind mesh X (usually pose 0); poses: K >= 2 example poses of the same vertices.
// Returns skeleton (heads = joints used as pivots, parents from cluster adjacency), influences
// (V rows, smooth, normalised, <= max_influences) and key_poses (K x B).
// kInvalidArgument for sizes or fewer than 2 poses; kDegenerate if the poses do not move.
Result<Rig> autoRig(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                    const AutoRigOptions& options = {}, AutoRigReport* report = nullptr);

}  // namespace odeskin
