// SPDX-License-Identifier: MIT
#include "gltf_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace odeskin::gltf {
namespace {

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

glm::dmat4 NodeTransform::local() const {
  if (matrix) return *matrix;
  const glm::dmat4 t = glm::translate(glm::dmat4(1.0), translation);
  const glm::dmat4 r = glm::mat4_cast(rotation);
  const glm::dmat4 s = glm::scale(glm::dmat4(1.0), scale);
  return t * r * s;
}

Result<std::vector<int>> nodeParents(const tinygltf::Model& model) {
  const int n = static_cast<int>(model.nodes.size());
  std::vector<int> parents(model.nodes.size(), -1);
  for (int p = 0; p < n; ++p) {
    for (int c : model.nodes[static_cast<std::size_t>(p)].children) {
      if (c < 0 || c >= n) {
        return parseError("node " + std::to_string(p) + " has child " + std::to_string(c) + ", outside 0.." +
                          std::to_string(n - 1));
      }
      if (parents[static_cast<std::size_t>(c)] != -1 || c == p) {
        return parseError("node " + std::to_string(c) + " is a child of more than one node (or of itself)");
      }
      parents[static_cast<std::size_t>(c)] = p;
    }
  }
  // With one parent per node, a chain longer than the node count can only be a cycle.
  for (int i = 0; i < n; ++i) {
    int steps = 0;
    for (int p = parents[static_cast<std::size_t>(i)]; p >= 0; p = parents[static_cast<std::size_t>(p)]) {
      if (++steps > n) return parseError("node " + std::to_string(i) + " is on a cycle of parents");
    }
  }
  return parents;
}

Result<std::vector<NodeTransform>> restTransforms(const tinygltf::Model& model) {
  std::vector<NodeTransform> out(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const tinygltf::Node& node = model.nodes[i];
    NodeTransform& t = out[i];
    auto bad = [&](const char* what) {
      return parseError("node " + std::to_string(i) + ": " + what + " must have the right length and finite values");
    };
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16 || !allFinite(node.matrix)) return bad("matrix (16)");
      glm::dmat4 m(1.0);
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[4 * static_cast<std::size_t>(c) + static_cast<std::size_t>(r)];  // column-major
      }
      // glTF's node matrix is a TRS (spec 3.5.2): a projective last row would be dropped silently.
      if (glm::row(m, 3) != glm::dvec4(0.0, 0.0, 0.0, 1.0)) {
        return parseError("node " + std::to_string(i) + ": matrix's last row must be 0, 0, 0, 1 (a node matrix is an "
                          "affine transform)");
      }
      t.matrix = m;
    }
    if (!node.translation.empty()) {
      if (node.translation.size() != 3 || !allFinite(node.translation)) return bad("translation (3)");
      t.translation = {node.translation[0], node.translation[1], node.translation[2]};
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4 || !allFinite(node.rotation)) return bad("rotation (4)");
      const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      if (glm::length(q) < 1e-12) return bad("rotation (a non-zero quaternion)");
      t.rotation = glm::normalize(q);
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3 || !allFinite(node.scale)) return bad("scale (3)");
      t.scale = {node.scale[0], node.scale[1], node.scale[2]};
    }
  }
  return out;
}

std::vector<glm::dmat4> globalMatrices(std::span<const NodeTransform> nodes, std::span<const int> parents) {
  std::vector<glm::dmat4> global(nodes.size());
  std::vector<char> done(nodes.size(), 0);
  std::vector<std::size_t> chain;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    // Climb to the nearest finished ancestor (or a root), then fill in on the way back down.
    chain.clear();
    for (int n = static_cast<int>(i); n >= 0 && !done[static_cast<std::size_t>(n)]; n = parents[static_cast<std::size_t>(n)]) {
      chain.push_back(static_cast<std::size_t>(n));
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int p = parents[*it];
      global[*it] = p >= 0 ? global[static_cast<std::size_t>(p)] * nodes[*it].local() : nodes[*it].local();
      done[*it] = 1;
    }
  }
  return global;
}

}  // namespace odeskin::gltf
