// SPDX-License-Identifier: MIT
#include "baseline_factory.hpp"

#include <string>

#include "linear_interpolation.hpp"
#include "odeskin_baseline.hpp"
#include "skinning_baseline.hpp"

namespace odeskin {
namespace {

template <typename T>
Result<std::unique_ptr<Baseline>> boxed(Result<T> built) {
  if (!built.ok()) return built.status();
  return std::unique_ptr<Baseline>(std::make_unique<T>(std::move(*built)));
}

}  // namespace

Result<std::unique_ptr<Baseline>> makeBaseline(BaselineMethod method, const std::vector<std::vector<Vec3>>& keys,
                                               const DeformAsset& asset, const BaselineOptions& options) {
  ODESKIN_TRY(checkKeyPoses(keys, asset.vertexCount(), "baselines"));
  if (keys.size() != asset.key_poses.size()) {
    return invalidArgument("baselines: " + std::to_string(keys.size()) + " key poses for an asset fitted on " +
                           std::to_string(asset.key_poses.size()));
  }
  switch (method) {
    case BaselineMethod::kLinear:
      return boxed(LinearInterpolation::create(keys));
    case BaselineMethod::kLbs:
    case BaselineMethod::kDqs: {
      ODESKIN_ASSIGN_OR_RETURN(BaselineRig rig, BaselineRig::fromAsset(asset));
      const SkinningMode mode = method == BaselineMethod::kDqs ? SkinningMode::kDualQuaternion : SkinningMode::kLinear;
      return std::unique_ptr<Baseline>(std::make_unique<SkinningBaseline>(std::move(rig), mode));
    }
    case BaselineMethod::kPsdLbs:
    case BaselineMethod::kPsdDqs: {
      ODESKIN_ASSIGN_OR_RETURN(BaselineRig rig, BaselineRig::fromAsset(asset));
      const SkinningMode mode = method == BaselineMethod::kPsdDqs ? SkinningMode::kDualQuaternion : SkinningMode::kLinear;
      return boxed(PoseSpaceDeformation::create(std::move(rig), keys, mode, options.psd));
    }
    case BaselineMethod::kFdCurve: {
      FdCurveOptions fd = options.fd;
      if (!fd.material) fd.material = options.dynamic_material;
      return boxed(FdCurveDeformer::create(asset, fd));
    }
    case BaselineMethod::kOdeskinStatic:
      return boxed(OdeskinBaseline::create(asset, options.static_material, method));
    case BaselineMethod::kOdeskinDynamic:
      return boxed(OdeskinBaseline::create(asset, options.dynamic_material, method));
  }
  return invalidArgument("baselines: unknown method " + std::to_string(static_cast<std::uint32_t>(method)));
}

}  // namespace odeskin
