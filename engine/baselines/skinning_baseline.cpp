// SPDX-License-Identifier: MIT
#include "skinning_baseline.hpp"

#include <algorithm>

#include "../kernels/lbs_job.hpp"

namespace odeskin {

SkinningBaseline::SkinningBaseline(BaselineRig rig, SkinningMode mode)
    : Baseline(rig.vertexCount()), rig_(std::move(rig)), mode_(mode) {}

BaselineMethod SkinningBaseline::method() const {
  return mode_ == SkinningMode::kDualQuaternion ? BaselineMethod::kDqs : BaselineMethod::kLbs;
}

Status SkinningBaseline::evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) {
  ODESKIN_TRY(checkFrame(frame, out, rig_.segmentCount(), rig_.boneCount()));
  LbsJob job;
  job.rest_positions = rig_.restPositions();
  job.influences = InfluencesView(rig_.influences());
  job.bones = rig_.frameBones(frame.segment, std::clamp(frame.tau, 0.0, 1.0), frame.bones, bones_);
  job.out_positions = out;
  job.skinning = mode_;
  return job.run();
}

}  // namespace odeskin
