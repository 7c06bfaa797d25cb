// SPDX-License-Identifier: MIT
// Internal to rig/: vertices clustered by consistent rigid motion across example poses, the bone
// initialisation of SSDR (Le & Deng 2012, section 4) and of James & Twigg (2005): each cluster has
// one rigid transform per pose, and each vertex belongs to the cluster whose transforms best
// reproduce it in every pose.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../mesh/adjacency.hpp"
#include "../offline/rigid_transform.hpp"

namespace odeskin {

// The example poses as the rig builders see them; all spans and pointers are required.
struct MotionData {
  std::span<const Vec3> rest;                          // V: bind mesh X
  const std::vector<std::vector<Vec3>>* poses = nullptr;  // K x V
  const VertexAdjacency* adjacency = nullptr;          // V rows
  double box = 1.0;                                    // longest box side of the bind mesh

  std::size_t vertexCount() const { return rest.size(); }
  std::size_t poseCount() const { return poses->size(); }
};

struct Clustering {
  std::vector<std::uint32_t> labels;                    // V: cluster of each vertex
  std::vector<std::vector<RigidTransform>> transforms;  // K x C: bind -> pose k, per cluster
  std::vector<double> vertex_error;                     // V: sum_k |T_{k,label} x_i - p_ki|^2
  double rms_error = 0.0;                               // sqrt(mean over k, i of |.|^2) / box
  std::size_t lloyd_rounds = 0;                         // Lloyd rounds run while the count grew

  std::size_t clusterCount() const { return transforms.empty() ? 0 : transforms[0].size(); }
};

struct ClusterOptions {
  int clusters = 0;        // 0: grown until the fit stops improving (see rigid_clusters.cpp),
  int min_clusters = 8;    //    from min_clusters (unless the fit is already good enough)
  int max_clusters = 32;   //    up to max_clusters
  int iterations = 20;     // assignment / refit rounds once the count is reached
  // A cycle of rounds ends with the state the cap would stop at, read off the cycle; the same
  // clustering to the bit in fewer rounds. False only to check that.
  bool skip_cycles = true;
};

// Every cluster is connected on the mesh (per mesh component) and has at least 3 non-collinear
// vertices. kDegenerate when the whole mesh cannot be aligned (all its vertices on a line).
Result<Clustering> clusterRigidMotion(const MotionData& motion, const ClusterOptions& options);

}  // namespace odeskin
