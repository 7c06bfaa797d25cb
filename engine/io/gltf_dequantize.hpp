// SPDX-License-Identifier: MIT
// A skinned mesh kept on an integer grid (KHR_mesh_quantization; internal to odeskin_gltf).
// glTF ignores a skinned mesh node's transform, so tools that quantize skinned meshes (gltfpack,
// glTF-Transform, `odeskin export --quantize`) fold the grid's dequantization D (scale, then
// offset) into every inverse bind matrix: S_j = G_j IBM_j D. odeskin needs rigid key poses, so the
// reader takes D back out of the skin and puts it into the mesh.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "../core/result.hpp"
#include "gltf_mesh.hpp"

namespace odeskin::gltf {

struct Dequantization {
  glm::dmat3 linear{1.0};  // invertible: a skin's shared scale, or an unskinned mesh node's world transform
  glm::dvec3 offset{0.0};
};

// D for a skin whose rest-pose skin matrices `rest_skin` (S_j = G_j IBM_j, in bone order) share
// one scale P other than the identity (polar decomposition S_j = R_j P); empty when every S_j is
// rigid, that is max |singular value - 1| <= `tolerance`. The offset is R_0^T t_0, which turns
// joint 0's rest transform about the origin: when the rest pose is the bind pose (the usual case)
// this gives back the mesh's coordinates before quantization; otherwise the bind space differs from
// them by a rigid motion, which no pose shows. `joint_names` name the joints in errors.
// kParseError naming the joint: a matrix that reflects, or one whose scale differs from joint 0's
// by more than `tolerance` (relative), with `what` (the skin) in front.
Result<std::optional<Dequantization>> sharedSkinScale(std::span<const glm::dmat4> rest_skin,
                                                      std::span<const std::string> joint_names, double tolerance,
                                                      const std::string& what);

// The mesh in D's coordinates: positions D q, morph-target deltas by D's linear part, normals by
// its inverse transpose, renormalized (a zero or non-finite normal stays as it is, for the reader's
// own check).
void dequantizeMesh(const Dequantization& d, MeshData& mesh);

// IBM_j D^-1 for every joint, so that G_j IBM_j maps D's coordinates.
void dequantizeInverseBinds(const Dequantization& d, std::vector<glm::dmat4>& inverse_bind);

}  // namespace odeskin::gltf
