// SPDX-License-Identifier: MIT
// Builds any of the eight in-between methods of issue 5 from the same inputs: the key poses and
// the DeformAsset fitted on them (runFitPipeline), so every method shares one rig.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "../core/result.hpp"
#include "../offline/deform_asset.hpp"
#include "../offline/material.hpp"
#include "baseline.hpp"
#include "fd_curve_deformer.hpp"
#include "pose_space_deformation.hpp"

namespace odeskin {

struct BaselineOptions {
  PsdOptions psd;
  // fd.material unset: the dynamic material below, so fd_curve and odeskin_dynamic solve one PDE.
  FdCurveOptions fd;
  Material static_material = staticMaterial();
  // nullopt: odeskin_dynamic (and fd_curve) keep the asset's own materials.
  std::optional<Material> dynamic_material = skinMaterial();
};

// `keys`: the K example poses the asset was fitted on (K x V, K = asset.key_poses.size()).
// Errors: kInvalidArgument when keys and asset disagree (counts, sizes), and each method's own.
Result<std::unique_ptr<Baseline>> makeBaseline(BaselineMethod method, const std::vector<std::vector<Vec3>>& keys,
                                               const DeformAsset& asset, const BaselineOptions& options = {});

}  // namespace odeskin
