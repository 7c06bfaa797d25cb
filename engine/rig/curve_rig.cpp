// SPDX-License-Identifier: MIT
#include "curve_rig.hpp"

#include <chrono>
#include <string>

namespace odeskin {

Result<CurveRig> buildCurveRig(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                               const CurveRigOptions& options) {
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (poses[k].size() != rest.size()) {
      return invalidArgument("curve rig: pose " + std::to_string(k) + " has " + std::to_string(poses[k].size()) +
                             " vertices, the bind mesh " + std::to_string(rest.size()));
    }
  }
  CurveRig out;
  ODESKIN_ASSIGN_OR_RETURN(out.curve_skeleton, buildCurveSkeleton(rest, faces, options.curves));
  out.seconds_topology = out.curve_skeleton.seconds_topology;
  out.seconds_curves = out.curve_skeleton.seconds_curves;
  const auto start = std::chrono::steady_clock::now();
  const CurveSkeleton& cs = out.curve_skeleton.skeleton;
  std::vector<std::vector<Vec3>> node_poses{cs.positions};
  for (const std::vector<Vec3>& pose : poses) node_poses.push_back(curveSkeletonPositions(cs, pose));
  ODESKIN_ASSIGN_OR_RETURN(out.animation, buildAnimationSkeleton(cs, node_poses, options.animation));
  out.rig.skeleton = toSkeleton(out.animation);
  out.seconds_skeleton = out.curve_skeleton.seconds_skeleton +
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (out.rig.skeleton.boneCount() == 0) {
    return degenerate("curve rig: the skeleton has no bone (the mesh is too small for two rings at level spacing " +
                      std::to_string(options.curves.level_spacing) + ")");
  }
  if (options.compute_weights) {
    const auto weights_start = std::chrono::steady_clock::now();
    Result<Influences> influences = distanceWeights(rest, faces, out.rig.skeleton, options.weights);
    if (!influences.ok()) return Status(influences.status().code(), "curve rig: " + influences.status().message());
    out.rig.influences = std::move(*influences);
    out.seconds_weights = std::chrono::duration<double>(std::chrono::steady_clock::now() - weights_start).count();
  }
  return out;
}

}  // namespace odeskin
