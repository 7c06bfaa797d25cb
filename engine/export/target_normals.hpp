// SPDX-License-Identifier: MIT
// NORMAL deltas for the compact export's morph targets, so viewers shade the corrective deformation
// instead of the skinned base shape. glTF adds weighted NORMAL deltas to the base NORMAL and
// normalises (spec 3.7.2.2), which is linear in the weights while the true normals are not, so:
//  - inside segment s each target's delta is the derivative of the unit vertex normals
//    (outputNormals) at the segment's start shape X + r^s in the direction of its field: first-order
//    exact, since the held sum there is exactly the start shape's unit normals;
//  - the segment's key correction E_s (weight 0 -> 1, held after) takes whatever makes the sum at
//    tau = 1 equal the end shape's normals, so every example pose is shaded exactly, however many
//    segments came before (the telescoping of mode_targets.hpp, for normals).
// Between keys the normals deviate by the second-order terms; buildTargetNormals measures that.
#pragma once

#include <span>
#include <vector>

#include "../core/result.hpp"
#include "mode_targets.hpp"

namespace odeskin {

struct TargetNormals {
  // One per ModeTargetSet::targets entry: NORMAL deltas at weight 1, indexed by output vertex
  // (the render vertices of a glTF-fitted asset), exact zeros left out.
  std::vector<SparseField> deltas;
  // Angles (radians) between the normal glTF computes from these deltas and the exact normal of
  // the export's bind-space shape, at the 31 interior points of 32 per segment on the exact weight
  // curves (the keys are exact): the mean, the largest, and the 99th percentile over the output
  // vertices of each vertex's largest. The largest come where the surface turns over between keys:
  // a normal blended linearly cannot follow a turn of more than about 90 degrees.
  double mean_angle = 0.0;
  double max_angle = 0.0;
  double vertex_p99_angle = 0.0;
  // (vertex, segment) pairs whose normals only blend the two keys' (by the correction's weight),
  // because the modes' linearisation strayed further there.
  std::size_t key_blended = 0;
};

// `base`: the V topology positions the targets start from (X + r^0). Every segment of `set` must
// carry its key correction (ModeTargetOptions::keep_zero_corrections), else kInvalidArgument.
Result<TargetNormals> buildTargetNormals(const DeformAsset& asset, std::span<const Vec3> base, const ModeTargetSet& set);

}  // namespace odeskin
