// SPDX-License-Identifier: MIT
// A rig from the iso-parametric curves of one mesh (thesis ch. 5): curve skeleton
// (curve_skeleton.hpp), animation skeleton with a template (animation_skeleton.hpp) and distance
// weights for its bones (distance_weights.hpp). Example poses, when given, only sharpen the joint
// placement (the largest turn over the poses, Sec. 5.4); the rig itself is read off the bind mesh,
// so it needs no motion at all, unlike the automatic rig of auto_rig.hpp.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "animation_skeleton.hpp"
#include "curve_skeleton.hpp"
#include "distance_weights.hpp"
#include "rig.hpp"

namespace odeskin {

struct CurveRigOptions {
  CurveSkeletonOptions curves;
  AnimationSkeletonOptions animation;
  DistanceWeightOptions weights;
  bool compute_weights = true;  // false: the skeleton only (rig.influences left empty)
};

struct CurveRig {
  CurveSkeletonResult curve_skeleton;
  AnimationSkeleton animation;
  Rig rig;  // skeleton (toSkeleton), influences (distance weights); no key poses
  // Table 5.1's stages: vertex (curve) identification, skeleton creation (curve skeleton and
  // animation skeleton), then the weights (not in the table).
  double seconds_topology = 0.0;  // the mesh's edges and triangle neighbours (once per mesh)
  double seconds_curves = 0.0;
  double seconds_skeleton = 0.0;
  double seconds_weights = 0.0;
};

// rest: the bind mesh; poses: example poses of the same vertices (may be empty; the bind mesh is
// always measured as well). Errors: buildCurveSkeleton's, buildAnimationSkeleton's (a pose of the
// wrong size), distanceWeights'; kDegenerate when the skeleton has no bone (a mesh too small to
// hold two rings).
Result<CurveRig> buildCurveRig(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                               const CurveRigOptions& options = {});

// The curve rig for a fit (`odeskin fit --rig curves`): buildCurveRig on the bind mesh with the
// example poses, then per-pose bone transforms by weighted Kabsch (fitBoneTransforms). `summary`
// receives one line for the user ("curves: 29 bones, template quadruped, ...").
Result<Rig> curveRigForPoses(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                             std::string* summary, const CurveRigOptions& options = {});

}  // namespace odeskin
