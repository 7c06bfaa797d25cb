// SPDX-License-Identifier: MIT
// A skeleton and what binds it to a mesh: weights and per-example-pose bone transforms. Any part
// may be missing on input; the rig stage fills it (Kabsch transforms, distance weights, or an
// automatic rig from the poses themselves).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "../core/types.hpp"
#include "../kernels/influences.hpp"
#include "../offline/rigid_transform.hpp"

namespace odeskin {

struct Skeleton {
  std::vector<std::string> names;     // B, may be empty strings
  std::vector<std::int32_t> parents;  // B, -1 for a root; a parent's index is not required to be smaller
  std::vector<Vec3> heads;            // B: the joint a bone turns about, in bind space (its pivot)
  std::vector<Vec3> tails;            // B: the bone's other end in bind space (== head if unknown)

  std::size_t boneCount() const { return heads.size(); }
};

struct Rig {
  Skeleton skeleton;
  Influences influences;                               // V rows over skeleton bones, or empty
  std::vector<std::vector<RigidTransform>> key_poses;  // K x B (bind -> example pose k), or empty
};

// kInvalidArgument naming the bone: sizes differ, a parent index out of range or a cycle, a
// non-finite joint. With `vertex_count` > 0 and influences present, checks them too
// (validateInfluences); with `pose_count` > 0 and key poses present, checks K x B and unit rotations.
Status validateRig(const Rig& rig, std::size_t vertex_count, std::size_t pose_count);

// How far linear blend skinning of `rest` with `rig`'s key poses lands from each of `poses`, and how
// far the poses move from `rest`, over every vertex of every pose; absolute lengths, which callers
// divide by the box they measure against. `rig` has a key pose per pose and influences for `rest`.
struct SkinningError {
  double max = 0.0;         // the largest distance
  double sum = 0.0;         // of every distance
  double motion_sum = 0.0;  // of every |pose - rest|
  std::size_t samples = 0;  // poses x vertices
};
SkinningError skinningError(std::span<const Vec3> rest, std::span<const std::vector<Vec3>> poses, const Rig& rig);

}  // namespace odeskin
