// SPDX-License-Identifier: MIT
// Weighted rigid alignment (Kabsch / Umeyama without scale): the rotation and translation that
// minimise sum_i w_i |R x_i + t - y_i|^2, and its use to recover per-pose bone transforms from
// skinning weights (PIPELINE.md 1).
#pragma once

#include <span>
#include <vector>

#include "../core/result.hpp"
#include "rig.hpp"

namespace odeskin {

// Points with weight 0 are ignored. kInvalidArgument for mismatched sizes, negative or non-finite
// weights, a non-finite point with a positive weight, or points so far apart that their products
// overflow; kDegenerate when the weighted points do
// not determine a rotation (fewer than 3 non-collinear points with weight > 0; numerically, the
// weighted cross-covariance's second singular value below 1e-9 of its first). When a reflection
// would fit better, the best proper rotation (det +1) is returned.
Result<RigidTransform> weightedKabsch(std::span<const Vec3> from, std::span<const Vec3> to, std::span<const double> weights);

// For every pose k and bone b, the bind -> pose k transform by weighted Kabsch of the bind mesh
// onto pose k with the bone's weights (K x B). A bone whose weighted points are degenerate inherits
// its parent's transform (or the identity for a root), as a skeleton with that bone fixed would.
// Vertices with less than 1e-3 of a bone's largest weight are left out of its alignment. Plain
// weighted Kabsch is biased where weights blend (LBS errors up to 0.06 on the 4-long cylinder),
// so the transforms are then refined by SSDR bone sweeps (Le & Deng 2012) to minimise the LBS
// error of each pose: with exact LBS data they are recovered exactly (the cylinder's .Tmat to
// their 6 printed digits).
// kInvalidArgument: no poses, sizes, positions not finite or too large or small for
// double-precision lengths (checkedPositionBox), influences or skeleton invalid.
Result<std::vector<std::vector<RigidTransform>>> fitBoneTransforms(std::span<const Vec3> rest,
                                                                   const std::vector<std::vector<Vec3>>& poses,
                                                                   const Influences& influences,
                                                                   const Skeleton& skeleton);

// The per-bone rigid fit alone (fitBoneTransforms without the SSDR sweeps): each bone is the
// weighted Kabsch of its own region, as a motion-capture or animation skeleton would be, not the
// transforms that minimise the pose's LBS error. Same inputs and errors as fitBoneTransforms.
Result<std::vector<std::vector<RigidTransform>>> fitRigidBoneTransforms(std::span<const Vec3> rest,
                                                                        const std::vector<std::vector<Vec3>>& poses,
                                                                        const Influences& influences,
                                                                        const Skeleton& skeleton);

}  // namespace odeskin
