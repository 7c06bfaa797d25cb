// SPDX-License-Identifier: MIT
#include "curve_rig.hpp"

#include <chrono>
#include <cstdio>
#include <string>

#include "../core/number_text.hpp"
#include "kabsch.hpp"

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
                      messageNumber(options.curves.level_spacing) + ")");
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

Result<Rig> curveRigForPoses(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                             std::string* summary, const CurveRigOptions& options) {
  ODESKIN_ASSIGN_OR_RETURN(CurveRig curve_rig, buildCurveRig(rest, faces, poses, options));
  Rig rig = std::move(curve_rig.rig);
  Result<std::vector<std::vector<RigidTransform>>> fitted = fitBoneTransforms(rest, poses, rig.influences, rig.skeleton);
  if (!fitted.ok()) return Status(fitted.status().code(), "curve rig: bone transforms: " + fitted.status().message());
  rig.key_poses = std::move(*fitted);
  if (summary) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "curves: %zu bones from the bind mesh's iso-curves (template %s; %.1f ms curves, %.1f ms skeleton, "
                  "%.1f ms weights), Kabsch transforms",
                  rig.skeleton.boneCount(), std::string(templateKindName(curve_rig.animation.used)).c_str(),
                  1e3 * curve_rig.seconds_curves, 1e3 * curve_rig.seconds_skeleton, 1e3 * curve_rig.seconds_weights);
    *summary = line;
  }
  return rig;
}

}  // namespace odeskin
