// SPDX-License-Identifier: MIT
#include "engine_bones.hpp"

#include <functional>

#include <string_view>
#include <unordered_map>

#include <glm/gtc/type_ptr.hpp>

namespace odeskin {

gpu::BoneMatrix boneMatrixFromColumnMajor(std::span<const float, 16> m) {
  // Entry (row r, column c) is m[4 c + r].
  gpu::BoneMatrix b;
  b.row0 = {m[0], m[4], m[8], m[12]};
  b.row1 = {m[1], m[5], m[9], m[13]};
  b.row2 = {m[2], m[6], m[10], m[14]};
  return b;
}

gpu::BoneMatrix boneMatrixFromMat4(const glm::mat4& m) {
  return boneMatrixFromColumnMajor(std::span<const float, 16>(glm::value_ptr(m), 16));
}

Result<std::vector<std::uint32_t>> engineJointOfEachBone(const RuntimeAsset& asset,
                                                         std::span<const std::string> engine_joints) {
  const std::vector<std::string>& names = asset.source().bone_names;
  if (names.empty()) {
    return invalidArgument("engine bones: the asset's bones have no names; "
                           "pass its " + std::to_string(asset.boneCount()) + " bones in its own order");
  }
  std::unordered_map<std::string_view, std::uint32_t> wanted;
  for (std::uint32_t b = 0; b < names.size(); ++b) {
    const auto [at, added] = wanted.emplace(names[b], b);
    if (!added) {
      return invalidArgument("engine bones: the asset's bones " + std::to_string(at->second) + " and " + std::to_string(b) +
                             " are both named '" + names[b] + "'; pass its bones in its own order");
    }
  }
  std::vector<std::uint32_t> joint_of_bone(names.size(), UINT32_MAX);
  for (std::uint32_t j = 0; j < engine_joints.size(); ++j) {
    const auto found = wanted.find(engine_joints[j]);
    if (found == wanted.end()) continue;
    std::uint32_t& slot = joint_of_bone[found->second];
    if (slot != UINT32_MAX) {
      return invalidArgument("engine bones: engine joints " + std::to_string(slot) + " and " + std::to_string(j) +
                             " are both named '" + engine_joints[j] + "', a bone of the asset");
    }
    slot = j;
  }
  for (std::uint32_t b = 0; b < names.size(); ++b) {
    if (joint_of_bone[b] == UINT32_MAX) {
      return invalidArgument("engine bones: no engine joint is named '" + names[b] + "' (bone " + std::to_string(b) +
                             " of the asset)");
    }
  }
  return joint_of_bone;
}

Status gatherBones(std::span<const std::uint32_t> joint_of_bone, std::span<const gpu::BoneMatrix> joints,
                   std::span<gpu::BoneMatrix> out) {
  if (out.size() != joint_of_bone.size()) {
    return invalidArgument("engine bones: " + std::to_string(out.size()) + " output bones for " +
                           std::to_string(joint_of_bone.size()) + " bones of the asset");
  }
  for (std::size_t b = 0; b < out.size(); ++b) {
    if (joint_of_bone[b] >= joints.size()) {
      return invalidArgument("engine bones: bone " + std::to_string(b) + " takes joint " +
                             std::to_string(joint_of_bone[b]) + " of " + std::to_string(joints.size()));
    }
  }
  // Gathering in place reads joints already overwritten: the bones came out wrong, with ok.
  const std::less<const gpu::BoneMatrix*> before;
  if (!out.empty() && !joints.empty() && before(out.data(), joints.data() + joints.size()) &&
      before(joints.data(), out.data() + out.size())) {
    return invalidArgument("engine bones: the joints and the output bones overlap; gather into another array");
  }
  for (std::size_t b = 0; b < out.size(); ++b) out[b] = joints[joint_of_bone[b]];
  return okStatus();
}

}  // namespace odeskin
