// SPDX-License-Identifier: MIT
// A glTF skin as odeskin's skeleton and influences (internal to odeskin_gltf); spec 3.7.3 "Skins".
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "../core/result.hpp"
#include "../kernels/influences.hpp"
#include "../rig/rig.hpp"
#include "gltf_accessor.hpp"
#include "gltf_mesh.hpp"
#include "gltf_weld.hpp"

namespace odeskin::gltf {

struct SkinData {
  std::vector<int> joint_nodes;          // B node indices, in skin.joints order (= bone order)
  std::vector<glm::dmat4> inverse_bind;  // B inverse bind matrices (identity when the skin has none)
  // Names: node names, or "joint<j>". Parents: the nearest ancestor node that is also a joint,
  // else -1. Heads: the bind-pose joint position, inverse(IBM) translation. Tails: the head of the
  // first joint (in bone order) whose parent it is, else the head.
  Skeleton skeleton;
};

// kParseError naming the skin: no joints, a joint node out of range or repeated, an
// inverseBindMatrices accessor that is not float MAT4 or has fewer elements than joints, an IBM
// whose last row is not (0, 0, 0, 1) or which is singular, or more values than `budget` has left.
Result<SkinData> readSkin(const tinygltf::Model& model, int skin_index, std::span<const int> parents,
                          DecodeBudget& budget);

// Heads and tails of `skin.skeleton` from its inverse bind matrices and parents (as SkinData says).
void placeJoints(SkinData& skin);

// Influences of the topology vertices: each takes its first render vertex's JOINTS_n/WEIGHTS_n,
// duplicate joints summed, weights divided by their sum, zero weights dropped, rows sorted by bone.
// kParseError naming the render vertex: a joint index >= bone_count, a negative weight, weights
// summing to 0; naming the topology vertex and both render vertices when two render vertices welded
// into it have normalised weights differing by more than 1e-4 for some joint.
// `warning` (when not null) is set when some vertices' weights do not sum to 1 (they are scaled to).
Result<Influences> topologyInfluences(const MeshData& mesh, const Welded& welded, std::uint32_t bone_count,
                                      std::string* warning = nullptr);

}  // namespace odeskin::gltf
