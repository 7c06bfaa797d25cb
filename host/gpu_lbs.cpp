// SPDX-License-Identifier: MIT
#include "gpu_lbs.hpp"

#include <string>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "shaders/lbs.spv.h"
#include "shaders/lbs_storage.spv.h"

namespace odeskin {

Result<GpuLbs> GpuLbs::create(const vk::Device& device, const PackedDeformData& data) {
  // LbsFastJob's own checks, so both paths accept exactly the same data.
  {
    std::vector<gpu::BoneMatrix> bones(data.bone_count);
    std::vector<gpu::Float4> out(data.vertex_count);
    LbsFastJob job;
    job.data = &data;
    job.bones = bones;
    job.out_positions = out;
    ODESKIN_TRY(job.validate());
  }
  GpuLbs lbs;
  lbs.bone_count_ = data.bone_count;
  // lbs.comp reads vertex_count, influence_layout and skinning of the shared push block; segment 0
  // is only a placeholder (deformPushConstants tolerates segment_count = 0).
  lbs.push_constants_ = deformPushConstants(data, 0);

  std::vector<vk::StaticBinding> statics;
  const std::pair<std::uint32_t, std::span<const std::byte>> arrays[] = {
      {ODESKIN_BINDING_REST_POSITIONS, std::as_bytes(std::span(data.rest_positions))},
      {ODESKIN_BINDING_INFLUENCE_OFFSETS, std::as_bytes(std::span(data.influence_offsets))},
      {ODESKIN_BINDING_INFLUENCES, std::as_bytes(std::span(data.influences))},
  };
  for (const auto& [binding, bytes] : arrays) {
    ODESKIN_ASSIGN_OR_RETURN(vk::Buffer buffer, vk::createStorageBuffer(device, bytes));
    statics.push_back({binding, buffer.handle()});
    lbs.inputs_.push_back(std::move(buffer));
  }

  SingleMeshDispatchDesc desc;
  desc.name = "lbs gpu";
  desc.spirv = kLbsSpirv;
  desc.storage_spirv = kLbsStorageSpirv;
  desc.vertex_count = data.vertex_count;
  desc.bone_count = data.bone_count;
  desc.skinning = data.skinning;
  desc.statics = statics;
  desc.push_constant_bytes = sizeof(gpu::DeformPushConstants);
  ODESKIN_ASSIGN_OR_RETURN(lbs.dispatch_, SingleMeshDispatch::create(device, desc));
  return lbs;
}

Status GpuLbs::validate(const GpuLbsFrame& frame) const {
  if (frame.bones.size() != bone_count_) {
    return invalidArgument("lbs gpu: bones has " + std::to_string(frame.bones.size()) + " entries, expected " +
                           std::to_string(bone_count_));
  }
  return okStatus();
}

Status GpuLbs::submit(const GpuLbsFrame& frame) {
  ODESKIN_TRY(validate(frame));
  return dispatch_.submit(frame.bones, {}, &push_constants_);
}

Status GpuLbs::run(const GpuLbsFrame& frame) {
  ODESKIN_TRY(submit(frame));
  return wait();
}

}  // namespace odeskin
