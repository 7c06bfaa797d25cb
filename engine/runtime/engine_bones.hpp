// SPDX-License-Identifier: MIT
// Bones from an engine's own animation system, for InstanceState::withBones. The runtime takes one
// skinning matrix per bone of the asset, in the asset's bone order, from bind space to pose space:
// for an asset fitted from a glTF skin, the joint matrix a glTF renderer computes (the joint node's
// global transform times its inverse bind matrix, glTF 2.0 section 3.7.3), in the skin's joints
// order. Engines keep their joints in their own order and their matrices column by column; these
// helpers bridge both. docs/runtime.md, "Bones from the engine", lists what goes wrong otherwise.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "../core/result.hpp"
#include "runtime_asset.hpp"

namespace odeskin {

// A 4x4 affine matrix stored column by column (glm::mat4, a glTF node's "matrix", OpenGL; also the
// sixteen floats of a DirectXMath XMFLOAT4X4 written for row vectors) as the runtime's three rows.
// The last row is dropped: skinning matrices have (0, 0, 0, 1) there.
gpu::BoneMatrix boneMatrixFromColumnMajor(std::span<const float, 16> m);
gpu::BoneMatrix boneMatrixFromMat4(const glm::mat4& m);

// For each bone of `asset`, in its order, the index of the engine's joint of the same name, so
// that joint_of_bone[b] = j with engine_joints[j] == asset.source().bone_names[b]. Engine joints
// the asset does not use are ignored. kInvalidArgument naming the bone when no engine joint has its
// name, naming the name when two engine joints (or two of the asset's bones) share a name the
// asset uses, and when the asset has no bone names (a nameless skeleton fitted through the API:
// pass its bones in its own order). odeskin's own rigs name bones auto_N, boneN (libigl) or
// root_N, junction_N, ... (curve rig), which an engine's joints rarely match.
Result<std::vector<std::uint32_t>> engineJointOfEachBone(const RuntimeAsset& asset,
                                                         std::span<const std::string> engine_joints);

// The engine's joint matrices in the asset's bone order: out[b] = joints[joint_of_bone[b]].
// kInvalidArgument when out and joint_of_bone differ in size, an index is past joints, or out
// overlaps joints (a reordering cannot be done in place).
Status gatherBones(std::span<const std::uint32_t> joint_of_bone, std::span<const gpu::BoneMatrix> joints,
                   std::span<gpu::BoneMatrix> out);

}  // namespace odeskin
