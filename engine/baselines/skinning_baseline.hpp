// SPDX-License-Identifier: MIT
// Plain skinning of the bind mesh with the shared rig: linear blend skinning
// (out_i = sum_b w_ib M_b X_i, thesis Eq 6.1) or dual-quaternion skinning (Kavan et al. 2008), with
// the frame's bones given by the caller (truth) or interpolated from the keys (keys protocol).
// Neither adds a corrective, so the key poses come back only as well as the rig fits them.
#pragma once

#include <vector>

#include "baseline.hpp"
#include "baseline_rig.hpp"

namespace odeskin {

class SkinningBaseline final : public Baseline {
 public:
  // mode: SkinningMode::kLinear (method "lbs") or kDualQuaternion ("dqs").
  SkinningBaseline(BaselineRig rig, SkinningMode mode);

  BaselineMethod method() const override;
  Status evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) override;

 private:
  BaselineRig rig_;
  SkinningMode mode_;
  std::vector<BoneTransform> bones_;  // keys protocol scratch
};

}  // namespace odeskin
