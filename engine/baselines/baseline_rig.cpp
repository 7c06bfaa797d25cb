// SPDX-License-Identifier: MIT
#include "baseline_rig.hpp"

#include <string>

#include "../offline/deform_player.hpp"
#include "../rig/kabsch.hpp"

namespace odeskin {

Result<BaselineRig> BaselineRig::fromAsset(const DeformAsset& asset) {
  ODESKIN_TRY(validateDeformAsset(asset));
  BaselineRig rig;
  rig.rest_positions_ = asset.rest_positions;
  rig.influences_ = asset.influences;
  rig.pivots_ = asset.bone_pivots;
  rig.parents_ = asset.bone_parents;
  rig.key_poses_ = asset.key_poses;
  rig.paths_ = boneKeyPaths(asset);
  return rig;
}

void BaselineRig::keyBones(std::size_t k, std::span<BoneTransform> out) const {
  for (std::size_t b = 0; b < pivots_.size() && b < out.size(); ++b) out[b] = key_poses_[k][b].matrix();
}

void BaselineRig::keyBones(std::uint32_t segment, double tau, std::span<BoneTransform> out) const {
  for (std::size_t b = 0; b < paths_.size() && b < out.size(); ++b) out[b] = paths_[b].at(segment, tau).matrix();
}

std::span<const BoneTransform> BaselineRig::frameBones(std::uint32_t segment, double tau,
                                                     std::span<const BoneTransform> given,
                                                     std::vector<BoneTransform>& scratch) const {
  if (!given.empty()) return given;
  scratch.resize(pivots_.size());
  keyBones(segment, tau, scratch);
  return scratch;
}

Result<std::vector<BoneTransform>> BaselineRig::fitFrameBones(std::span<const Vec3> frame, SkeletonFit fit) const {
  if (frame.size() != rest_positions_.size()) {
    return invalidArgument("fit frame bones: the frame has " + std::to_string(frame.size()) +
                           " vertices, the bind mesh " + std::to_string(rest_positions_.size()));
  }
  Skeleton skeleton;
  skeleton.heads = pivots_;
  skeleton.tails = pivots_;
  skeleton.names.assign(pivots_.size(), std::string());
  skeleton.parents = parents_.empty() ? std::vector<std::int32_t>(pivots_.size(), -1) : parents_;
  const std::vector<std::vector<Vec3>> poses{std::vector<Vec3>(frame.begin(), frame.end())};
  Result<std::vector<std::vector<RigidTransform>>> fitted =
      fit == SkeletonFit::kPerBoneRigid ? fitRigidBoneTransforms(rest_positions_, poses, influences_, skeleton)
                                        : fitBoneTransforms(rest_positions_, poses, influences_, skeleton);
  if (!fitted.ok()) return Status(fitted.status().code(), "fit frame bones: " + fitted.status().message());
  std::vector<BoneTransform> bones;
  bones.reserve(pivots_.size());
  for (const RigidTransform& t : (*fitted)[0]) bones.push_back(t.matrix());
  return bones;
}

}  // namespace odeskin
