// SPDX-License-Identifier: MIT
// Pose arithmetic for the glTF reader (internal to odeskin_gltf): morphing (spec 3.7.2.2: deltas
// are applied before skinning) and the rigid part of a skin matrix for the rig's key poses.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "../core/types.hpp"
#include "../offline/rigid_transform.hpp"

namespace odeskin::gltf {

// base_i + sum_k weights_k deltas_k,i. `deltas` T x V, `weights` T.
std::vector<Vec3> morph(std::span<const Vec3> base, const std::vector<std::vector<Vec3>>& deltas,
                        std::span<const double> weights);

// Polar decomposition of the linear part of an affine `skin` matrix, A = R P (SVD: A = U S V^T,
// R = U V^T), with the matrix's translation. `deviation` receives max_i |s_i - 1|, how far P is
// from the identity (scale or shear). Empty when A reflects (det A <= 0).
std::optional<RigidTransform> rigidPart(const glm::dmat4& skin, double& deviation);

}  // namespace odeskin::gltf
