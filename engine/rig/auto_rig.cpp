// SPDX-License-Identifier: MIT
// The automatic rig, in the order of Le & Deng's SSDR (2012) with a skeleton read off the clusters:
//  1. Rigid-motion clusters with per-pose Kabsch transforms (rigid_clusters.cpp); their count is
//     options.bones, or grown until the fit stops improving.
//  2. Parents and joints from the cluster graph (cluster_skeleton.hpp).
//  3. Weights: the hard assignment diffused over the vertex graph (kPriorSmoothing umbrella steps)
//     is the smooth prior; per vertex, the best non-negative weights over its few prior bones,
//     pulled towards the prior (vertex_weight_fit.cpp), at most max_influences, summing to 1.
//  4. Bone transforms refitted to those weights by SSDR bone sweeps (bone_fit.hpp); 3 and 4
//     alternate kWeightRounds times, each round's prior being the last weights lightly smoothed,
//     then the joints are placed again with the final transforms.
#include "auto_rig.hpp"

#include <algorithm>
#include <cmath>
#include <string>


#include "../offline/residual_fit.hpp"
#include "bone_fit.hpp"
#include "cluster_skeleton.hpp"
#include "rigid_clusters.hpp"
#include "vertex_weight_fit.hpp"
#include "weight_rows.hpp"
#include "../core/parallel.hpp"
#include "../core/position_box.hpp"

namespace odeskin {
namespace {

// The weight schedule, chosen on cat-poses, horse-gallop and the cylinder (mean LBS error / box,
// largest weight step across one mesh edge):
//  - the first prior is the hard assignment diffused by kPriorSmoothing umbrella steps (about
//    sqrt(30) ~ 5 rings each side of a cluster boundary);
//  - each round's prior is the previous round's weights smoothed by kReSmoothing steps, and its
//    pull starts as strong as a typical misfit and decays by kPullDecay per round, so weights move
//    away from the diffusion only where the poses keep asking for it.
// Measured with 32 bones: one round with a weak pull (0.05) gives cat 1.56e-3 / step 0.91, horse
// 1/9 4.9e-4 / 1.0; this schedule gives cat 1.56e-3 / 0.63, horse 1/9 2.6e-4 / 0.54, horse keys
// 6.2e-4 / 0.61 (4 bones on the cylinder: 5.9e-3 -> 3.3e-3).
constexpr int kPriorSmoothing = 30;
constexpr int kReSmoothing = 2;
constexpr int kWeightRounds = 6;
constexpr double kFirstPull = 1.0;
constexpr double kPullDecay = 0.6;
constexpr int kBoneSweeps = 5;
// Poses whose vertices all stay within this fraction of the longest box side of the bind mesh
// carry no motion to derive bones from.
constexpr double kStaticMotion = 1e-9;

Status checkInput(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                  const AutoRigOptions& options) {
  if (rest.empty()) return invalidArgument("auto rig: the bind mesh has no vertices");
  if (poses.size() < 2) return invalidArgument("auto rig: needs at least 2 example poses, got " + std::to_string(poses.size()));
  ODESKIN_TRY(checkedPositionBox(rest, "auto rig: the bind mesh").status());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (poses[k].size() != rest.size()) {
      return invalidArgument("auto rig: pose " + std::to_string(k) + " has " + std::to_string(poses[k].size()) +
                             " vertices, the bind mesh " + std::to_string(rest.size()));
    }
    ODESKIN_TRY(checkedPositionBox(poses[k], "auto rig: pose " + std::to_string(k)).status());
  }
  if (options.bones < 0 || static_cast<std::size_t>(options.bones) * 3 > rest.size()) {
    return invalidArgument("auto rig: bones must be 0 (automatic) or at most a third of the " +
                           std::to_string(rest.size()) + " vertices, got " + std::to_string(options.bones));
  }
  if (options.max_influences < 1) {
    return invalidArgument("auto rig: max_influences must be at least 1, got " + std::to_string(options.max_influences));
  }
  if (options.iterations < 1) {
    return invalidArgument("auto rig: iterations must be at least 1, got " + std::to_string(options.iterations));
  }
  return checkFaces(faces, rest.size(), "auto rig");
}

void measure(const MotionData& m, const Rig& rig, AutoRigReport& report) {
  const SkinningError e = skinningError(m.rest, *m.poses, rig);
  const double samples = static_cast<double>(e.samples);
  report.bones = static_cast<int>(rig.skeleton.boneCount());
  report.max_error = e.max / m.box;
  report.mean_error = e.sum / samples / m.box;
  report.mean_motion = e.motion_sum / samples / m.box;
}

}  // namespace

Result<Rig> autoRig(std::span<const Vec3> rest, const FaceList& faces, const std::vector<std::vector<Vec3>>& poses,
                    const AutoRigOptions& options, AutoRigReport* report) {
  ODESKIN_TRY(checkInput(rest, faces, poses, options));
  const VertexAdjacency adjacency = vertexAdjacency(faces, rest.size());
  MotionData motion{rest, &poses, &adjacency, longestBoxSide(rest)};
  if (!(motion.box > 0.0)) return degenerate("auto rig: the bind mesh is a single point");
  double moved = 0.0;
  for (const std::vector<Vec3>& pose : poses) {
    for (std::size_t i = 0; i < rest.size(); ++i) moved = std::max(moved, glm::length(pose[i] - rest[i]));
  }
  if (moved <= kStaticMotion * motion.box) {
    return degenerate("auto rig: no vertex moves between the bind mesh and the example poses");
  }

  ClusterOptions cluster_options;
  cluster_options.clusters = options.bones;
  cluster_options.iterations = options.iterations;
  ODESKIN_ASSIGN_OR_RETURN(Clustering clusters, clusterRigidMotion(motion, cluster_options));
  std::vector<std::vector<RigidTransform>> transforms = std::move(clusters.transforms);

  Rig rig;
  // Parents now (a bone the sweeps cannot align follows its parent); joints again at the end.
  rig.skeleton = skeletonFromClusters(motion, clusters.labels, transforms);
  std::vector<WeightRow> prior(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) prior[i] = {{clusters.labels[i], 1.0}};
  smoothRows(prior, adjacency, kPriorSmoothing, 0.5);
  double pull = kFirstPull;
  for (int round = 0; round < kWeightRounds; ++round, pull *= kPullDecay) {
    std::vector<WeightRow> fitted = fitVertexWeights(motion, transforms, prior, options.max_influences, pull);
    rig.influences = pruneRows(fitted, options.max_influences);
    // The next round is pulled towards these weights, smoothed: the weights can move far from the
    // first diffusion where the poses ask for it, a little at a time, and stay smooth.
    prior = std::move(fitted);
    smoothRows(prior, adjacency, kReSmoothing, 0.5);
    const BoneFitProblem problem = makeBoneFitProblem(rest, rig.influences, rig.skeleton.parents);
    parallelFor(std::size_t{0}, poses.size(), [&](std::size_t k) {
      refineBoneTransforms(problem, poses[k], transforms[k], kBoneSweeps);
    });
  }
  rig.skeleton = skeletonFromClusters(motion, clusters.labels, transforms);
  rig.key_poses = std::move(transforms);
  if (Status valid = validateRig(rig, rest.size(), poses.size()); !valid.ok()) {
    return internalError("auto rig built an invalid rig: " + valid.message());
  }
  if (report != nullptr) measure(motion, rig, *report);
  return rig;
}

}  // namespace odeskin
