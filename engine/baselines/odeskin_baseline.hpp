// SPDX-License-Identifier: MIT
// odeskin itself behind the common interface: the fitted DeformAsset played by the reference
// kernel (DeformPlayer time bases + referenceJob, PIPELINE.md 3), with every curve given one
// material: staticMaterial() for "odeskin_static" (gamma_n = tau: a linear blend of the bind-space
// correctives) or a dynamic one (default skinMaterial()) for "odeskin_dynamic". The carried rates
// are re-chained for that material (chainSegmentRates). The skeleton comes from the caller (truth)
// or from the key transforms (keys protocol, the same RigidKeyPath as DeformPlayer::bonesAt).
#pragma once

#include <optional>
#include <vector>

#include "../core/result.hpp"
#include "../offline/deform_asset.hpp"
#include "../offline/deform_player.hpp"
#include "../offline/material.hpp"
#include "baseline.hpp"

namespace odeskin {

class OdeskinBaseline final : public Baseline {
 public:
  // `material`: every curve's material; nullopt keeps the asset's own materials. `method`:
  // kOdeskinStatic or kOdeskinDynamic (the name it reports). Errors: kInvalidArgument for another
  // method, those of validateDeformAsset and DeformPlayer::create (a degenerate or resonant material).
  static Result<OdeskinBaseline> create(const DeformAsset& asset, std::optional<Material> material,
                                        BaselineMethod method);

  BaselineMethod method() const override { return method_; }
  Status evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) override;

  const DeformAsset& asset() const { return asset_; }

 private:
  OdeskinBaseline(DeformAsset asset, DeformPlayer player, BaselineMethod method);

  DeformAsset asset_;
  DeformPlayer player_;
  BaselineMethod method_;
  std::vector<ModeBasisValue> basis_;   // scratch, player_.basisSize()
  std::vector<BoneTransform> bones_;    // keys protocol scratch
};

}  // namespace odeskin
