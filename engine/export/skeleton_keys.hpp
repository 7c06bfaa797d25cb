// SPDX-License-Identifier: MIT
// The skeletal animation of the compact export. Every bone b is a joint node whose bind frame is
// the translation J_b to its pivot (so its inverse bind matrix is J_b^-1); its world transform at
// time t is G_b(t) = T_b(t) J_b with T_b the player's bone transform (DeformPlayer::bonesAt), and
// its node keeps the local part G_parent^-1 G_b as translation + rotation (rigid, no scale). Joint
// matrix G_b J_b^-1 = T_b: glTF's skinning reproduces the player's LBS. Keys are CUBICSPLINE with
// tangents from second-order finite differences of the local path inside each segment (separate
// in- and out-tangents at segment joins), or LINEAR keys (key_interpolation.hpp), placed adaptively
// until the composed world transforms, applied to the bind-space positions of the vertices each
// bone influences, are within tolerance. A LINEAR rotation is checked both as glTF's spherical
// interpolation and as the normalized component-wise one that importers keeping quaternion curves
// per component play (Blender), so either stays within tolerance.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "../core/result.hpp"
#include "../offline/deform_player.hpp"
#include "key_interpolation.hpp"

namespace odeskin {

struct SkeletonKeyOptions {
  double position_tolerance = 1e-5;  // absolute, same unit as the mesh
  double min_key_gap = 1e-5;         // in t: intervals are not halved below this
  KeyInterpolation interpolation = KeyInterpolation::kCubicSpline;
};

struct SkeletonKeys {
  std::vector<std::int32_t> parents;  // B: parent bone, or -1 for a child of the skeleton root
  KeyInterpolation interpolation = KeyInterpolation::kCubicSpline;
  std::vector<double> times;          // global t of every key, strictly increasing
  // keys x bones, key-major: local translation and rotation with their in- and out-tangents (d/dt;
  // LINEAR keys leave them unused).
  // Rotations are unit quaternions, signs chosen so consecutive keys are on the same hemisphere.
  std::vector<Vec3> translations, translation_in, translation_out;
  std::vector<glm::dquat> rotations, rotation_in, rotation_out;
  // Measured on a dense check: max over bones of |G~_b J_b^-1 x - T_b x| bounded over a sphere around
  // the bind-space positions (at the keys) of the vertices the bone influences.
  double max_position_error = 0.0;
};

// kInvalidArgument for a bone hierarchy with a cycle, or non-positive options.
Result<SkeletonKeys> placeSkeletonKeys(const DeformAsset& asset, const DeformPlayer& player,
                                       const SkeletonKeyOptions& options);

// Order in which every parent comes before its children (kInvalidArgument naming a bone on a cycle).
Result<std::vector<std::uint32_t>> parentsFirst(std::span<const std::int32_t> parents);

}  // namespace odeskin
