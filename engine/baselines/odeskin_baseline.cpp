// SPDX-License-Identifier: MIT
#include "odeskin_baseline.hpp"

#include <algorithm>

#include "../offline/residual_fit.hpp"

namespace odeskin {

OdeskinBaseline::OdeskinBaseline(DeformAsset asset, DeformPlayer player, BaselineMethod method)
    : Baseline(asset.vertexCount()), asset_(std::move(asset)), player_(std::move(player)), method_(method) {
  basis_.resize(player_.basisSize());
  bones_.resize(asset_.bone_count);
}

Result<OdeskinBaseline> OdeskinBaseline::create(const DeformAsset& asset, std::optional<Material> material,
                                                BaselineMethod method) {
  if (method != BaselineMethod::kOdeskinStatic && method != BaselineMethod::kOdeskinDynamic) {
    return invalidArgument("odeskin baseline: method " + std::string(baselineMethodName(method)) +
                           " is not an odeskin variant");
  }
  ODESKIN_TRY(validateDeformAsset(asset));
  DeformAsset copy = asset;
  if (material) {
    copy.materials = {*material};
    copy.curve_materials.assign(copy.curveCount(), 0u);
    ODESKIN_TRY(chainSegmentRates(copy));
  }
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(copy));
  return OdeskinBaseline(std::move(copy), std::move(player), method);
}

Status OdeskinBaseline::evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) {
  ODESKIN_TRY(checkFrame(frame, out, player_.segmentCount(), asset_.bone_count));
  const double tau = std::clamp(frame.tau, 0.0, 1.0);
  player_.basisAt(tau, basis_);
  std::span<const BoneTransform> bones = frame.bones;
  if (bones.empty()) {
    player_.bonesAt(asset_, frame.segment, tau, bones_);
    bones = bones_;
  }
  return referenceJob(asset_, frame.segment, basis_, bones, out).run();
}

}  // namespace odeskin
