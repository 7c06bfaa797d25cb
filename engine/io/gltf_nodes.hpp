// SPDX-License-Identifier: MIT
// The glTF node hierarchy (internal to odeskin_gltf): local transforms (matrix, or T * R * S) and
// global transforms as products along the parent chain (spec 3.5.2 "Transformations").
#pragma once

#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "../core/result.hpp"

namespace odeskin::gltf {

struct NodeTransform {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z); glTF stores x, y, z, w
  glm::dvec3 scale{1.0};
  std::optional<glm::dmat4> matrix;  // node.matrix when the file gives one (then never animated)

  glm::dmat4 local() const;
};

// Parent of every node, -1 for a root. kParseError naming the node: a child index out of range, a
// node listed as the child of two nodes, a cycle.
Result<std::vector<int>> nodeParents(const tinygltf::Model& model);

// The nodes' own (unanimated) transforms. kParseError naming the node: a translation, rotation,
// scale or matrix array of the wrong length or with non-finite values, a matrix whose last row is
// not 0, 0, 0, 1.
Result<std::vector<NodeTransform>> restTransforms(const tinygltf::Model& model);

// Global matrices: parent global x local, for every node. `parents` must be acyclic (nodeParents).
std::vector<glm::dmat4> globalMatrices(std::span<const NodeTransform> nodes, std::span<const int> parents);

}  // namespace odeskin::gltf
