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
  // 0: chosen from the motion: grown while the clusters' RMS fit error is above 1e-3 of the box
  // and improves by at least 1% per added bone, from 8 (fewer if the fit is already that good) to
  // 32 (rigid_clusters.cpp). Otherwise at most a third of the vertices; fewer come out when the
  // mesh has too few distinct rigid parts to hold them (see AutoRigReport::bones).
  int bones = 0;
  int max_influences = 4;    // >= 1
  int iterations = 20;       // >= 1: cluster / refit rounds each time the bone count grows
};

// Errors are measured over every pose and vertex, relative to the bind mesh's longest box side.
struct AutoRigReport {
  int bones = 0;
  double max_error = 0.0;    // worst vertex of LBS(rig) vs the example poses, / longest box side
  double mean_error = 0.0;   // mean vertex error, / longest box side
  double mean_motion = 0.0;  // mean vertex displacement from the bind mesh to the poses, / longest box side
};

// rest: the bind mesh X (usually pose 0); poses: K >= 2 example poses of the same vertices.
// Returns skeleton (heads = joints used as pivots, parents from cluster adjacency, tails = bone
// centroids, names "auto_<b>"), influences (V rows, smooth, normalised, <= max_influences) and
// key_poses (K x B; the identity for every bone in a pose equal to the bind mesh).
// Measured on cat-poses (10 poses, 7207 vertices, ~1.3 s on one core): 32 bones, mean error
// 1/120 of the mean motion; horse-gallop frames 1, 5, .., 25: 32 bones, 1/84.
// kInvalidArgument for sizes, positions not finite or too large or small for double-precision
// lengths (checkedPositionBox), bad faces, options out of range or fewer than 2 poses; kDegenerate
// if the poses do not move or the mesh is a line.
Result<Rig> autoRig(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                    const AutoRigOptions& options = {}, AutoRigReport* report = nullptr);

}  // namespace odeskin
