// SPDX-License-Identifier: MIT
#include "pose_space_deformation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "../kernels/dual_quaternion.hpp"
#include "../kernels/lbs_job.hpp"

namespace odeskin {
namespace {

// A skinning map whose linear part has |det| below this cannot carry a bind-space corrective: its
// inverse would amplify the residual more than a thousandfold. Rotations have det 1; LBS blends of
// bones less than ~170 degrees apart stay far above it.
constexpr double kMinDeterminant = 1e-3;

glm::dquat boneRotation(const BoneTransform& bone) {
  glm::dquat q = glm::quat_cast(nearestRotation(glm::dmat3(bone)));
  return q.w < 0.0 ? -q : q;
}

// Rotation vector of a unit quaternion with w >= 0 (angle in [0, pi]).
Vec3 rotationVector(const glm::dquat& q) {
  const Vec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  if (s < 1e-300) return Vec3(0.0);
  return v * (2.0 * std::atan2(s, q.w) / s);
}

}  // namespace

void poseSpaceCoordinates(std::span<const BoneTransform> bones, std::span<const std::int32_t> parents,
                          std::span<const double> bone_scales, std::span<double> out) {
  for (std::size_t b = 0; b < bones.size(); ++b) {
    glm::dquat q = boneRotation(bones[b]);
    if (!parents.empty() && parents[b] >= 0) {
      q = glm::inverse(boneRotation(bones[static_cast<std::size_t>(parents[b])])) * q;
      if (q.w < 0.0) q = -q;
    }
    const Vec3 v = rotationVector(q) * (bone_scales.empty() ? 1.0 : bone_scales[b]);
    out[3 * b] = v.x;
    out[3 * b + 1] = v.y;
    out[3 * b + 2] = v.z;
  }
}

PoseSpaceDeformation::PoseSpaceDeformation(BaselineRig rig, SkinningMode mode, RbfInterpolator rbf)
    : Baseline(rig.vertexCount()), rig_(std::move(rig)), mode_(mode), rbf_(std::move(rbf)) {}

Result<PoseSpaceDeformation> PoseSpaceDeformation::create(BaselineRig rig, const std::vector<std::vector<Vec3>>& keys,
                                                          SkinningMode mode, const PsdOptions& options) {
  const char* who = mode == SkinningMode::kDualQuaternion ? "psd_dqs" : "psd_lbs";
  if (mode != SkinningMode::kLinear && mode != SkinningMode::kDualQuaternion) {
    return invalidArgument(std::string(who) + ": unknown skinning mode");
  }
  ODESKIN_TRY(checkKeyPoses(keys, rig.vertexCount(), who));
  if (keys.size() != rig.keyCount()) {
    return invalidArgument(std::string(who) + ": " + std::to_string(keys.size()) + " key poses for a rig of " +
                           std::to_string(rig.keyCount()) + " key skeletons");
  }
  const std::uint32_t bone_count = rig.boneCount();
  const std::size_t v_count = rig.vertexCount();
  std::vector<std::int32_t> parents;
  if (options.relative_to_parent) parents.assign(rig.parents().begin(), rig.parents().end());
  std::vector<double> scales;
  if (options.weight_bones_by_influence) {
    scales.assign(bone_count, 0.0);
    const Influences& in = rig.influences();
    for (std::size_t j = 0; j < in.bones.size(); ++j) scales[in.bones[j]] += in.weights[j];
    for (double& s : scales) s = std::sqrt(s / static_cast<double>(v_count));
  }

  std::vector<std::vector<Vec3>> correctives(keys.size(), std::vector<Vec3>(v_count));
  std::vector<double> examples(keys.size() * 3 * bone_count);
  std::vector<BoneTransform> bones(bone_count);
  const InfluencesView view(rig.influences());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    rig.keyBones(k, bones);
    poseSpaceCoordinates(bones, parents, scales, std::span<double>(examples).subspan(k * 3 * bone_count, std::size_t{3} * bone_count));
    const std::vector<DualQuaternion> dual = toDualQuaternions(bones);
    for (std::size_t i = 0; i < v_count; ++i) {
      const SkinTransform skin = skinTransform(mode, view, bones, dual, i);
      if (!(std::abs(glm::determinant(skin.linear)) >= kMinDeterminant)) {
        return illPosed(std::string(who) + ": vertex " + std::to_string(i) + " has a singular skinning map at key " +
                        std::to_string(k) + " (bones with nearly opposed rotations)");
      }
      correctives[k][i] = glm::inverse(skin.linear) * (keys[k][i] - skin.apply(rig.restPositions()[i]));
    }
  }
  Result<RbfInterpolator> rbf = RbfInterpolator::create(examples, 3 * static_cast<std::size_t>(bone_count), options.rbf);
  if (!rbf.ok()) return Status(rbf.status().code(), std::string(who) + ": " + rbf.status().message());
  PoseSpaceDeformation psd(std::move(rig), mode, std::move(*rbf));
  psd.parents_ = std::move(parents);
  psd.bone_scales_ = std::move(scales);
  psd.correctives_ = std::move(correctives);
  psd.corrected_.resize(v_count);
  psd.query_.resize(3 * static_cast<std::size_t>(bone_count));
  psd.weights_.resize(psd.correctives_.size());
  return psd;
}

BaselineMethod PoseSpaceDeformation::method() const {
  return mode_ == SkinningMode::kDualQuaternion ? BaselineMethod::kPsdDqs : BaselineMethod::kPsdLbs;
}

void PoseSpaceDeformation::exampleWeights(std::span<const BoneTransform> bones, std::span<double> out) const {
  std::vector<double> query(3 * bones.size());
  poseSpaceCoordinates(bones, parents_, bone_scales_, query);
  rbf_.weights(query, out);
}

Status PoseSpaceDeformation::evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) {
  ODESKIN_TRY(checkFrame(frame, out, rig_.segmentCount(), rig_.boneCount()));
  const std::span<const BoneTransform> bones =
      rig_.frameBones(frame.segment, std::clamp(frame.tau, 0.0, 1.0), frame.bones, bones_);
  poseSpaceCoordinates(bones, parents_, bone_scales_, query_);
  rbf_.weights(query_, weights_);
  const std::span<const Vec3> rest = rig_.restPositions();
  for (std::size_t i = 0; i < rest.size(); ++i) {
    Vec3 c(0.0);
    for (std::size_t k = 0; k < correctives_.size(); ++k) c += weights_[k] * correctives_[k][i];
    corrected_[i] = rest[i] + c;
  }
  LbsJob job;
  job.rest_positions = corrected_;
  job.influences = InfluencesView(rig_.influences());
  job.bones = bones;
  job.out_positions = out;
  job.skinning = mode_;
  return job.run();
}

}  // namespace odeskin
