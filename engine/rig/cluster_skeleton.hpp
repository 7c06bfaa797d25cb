// SPDX-License-Identifier: MIT
// Internal to rig/: the skeleton of a rigid-motion clustering. Parents come from a maximum spanning
// tree of the cluster adjacency graph (edge weight: mesh edges between the two clusters, so bones
// hinge where they share the most boundary), rooted at the largest cluster of each connected part.
// A child's head is the joint: the point both bones move alike over all poses,
//   j = argmin sum_k |T_child,k j - T_parent,k j|^2 + mu |j - b|^2,
// with b the centroid of the mesh edges the two clusters share and mu = kJointPull x K. mu fixes
// the joint along a hinge axis (where the poses do not determine it) and keeps it near the boundary
// when the two bones barely turn relative to each other. Tails and root heads are cluster centroids.
#pragma once

#include <span>
#include <vector>

#include "rig.hpp"
#include "rigid_clusters.hpp"

namespace odeskin {

// `labels`: V cluster indices < C; `transforms`: K x C. Every cluster must have a vertex.
Skeleton skeletonFromClusters(const MotionData& motion, std::span<const std::uint32_t> labels,
                              const std::vector<std::vector<RigidTransform>>& transforms);

}  // namespace odeskin
