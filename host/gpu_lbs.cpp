// SPDX-License-Identifier: MIT
#include "gpu_lbs.hpp"

#include <cstring>
#include <string>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "shaders/lbs.spv.h"

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
  lbs.device_ = &device;
  lbs.vertex_count_ = data.vertex_count;
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
  const VkDeviceSize out_bytes = static_cast<VkDeviceSize>(data.vertex_count) * sizeof(gpu::Float4);
  ODESKIN_ASSIGN_OR_RETURN(lbs.out_positions_,
                           vk::Buffer::create(device, out_bytes < 16 ? 16 : out_bytes, vk::kOutputBufferUsage));
  statics.push_back({ODESKIN_BINDING_OUT_POSITIONS, lbs.out_positions_.handle()});

  // Per-frame buffer: bones, then their dual quaternions (bound in either mode, written for DQS).
  const std::size_t raw_bones = static_cast<std::size_t>(data.bone_count) * sizeof(gpu::BoneMatrix);
  const VkDeviceSize bones_bytes = raw_bones < 16 ? 16 : raw_bones;
  const std::size_t raw_dual_quats = static_cast<std::size_t>(data.bone_count) * sizeof(gpu::DualQuat);
  const VkDeviceSize dual_quat_bytes = raw_dual_quats < 16 ? 16 : raw_dual_quats;
  if (bones_bytes > device.limits().maxStorageBufferRange || dual_quat_bytes > device.limits().maxStorageBufferRange) {
    return unavailable("lbs gpu: " + std::to_string(data.bone_count) + " bones exceed maxStorageBufferRange");
  }
  const VkDeviceSize alignment = device.limits().minStorageBufferOffsetAlignment;
  lbs.dual_quat_offset_ = alignment == 0 ? bones_bytes : (bones_bytes + alignment - 1) / alignment * alignment;
  lbs.dual_quaternion_ = data.skinning == SkinningMode::kDualQuaternion;
  if (lbs.dual_quaternion_) lbs.dual_quats_.resize(data.bone_count);
  const vk::FrameBinding frame_bindings[] = {
      {ODESKIN_BINDING_BONES, 0, bones_bytes},
      {ODESKIN_BINDING_BONE_DUAL_QUATS, lbs.dual_quat_offset_, dual_quat_bytes},
  };
  vk::ComputeDispatcherDesc desc;
  desc.spirv = kLbsSpirv;
  desc.static_bindings = statics;
  desc.frame_bindings = frame_bindings;
  desc.frame_bytes = lbs.dual_quat_offset_ + dual_quat_bytes;
  desc.push_constant_bytes = sizeof(gpu::DeformPushConstants);
  desc.frames_in_flight = 2;
  ODESKIN_ASSIGN_OR_RETURN(lbs.dispatcher_, vk::ComputeDispatcher::create(device, desc));
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
  if (vertex_count_ == 0) return okStatus();
  ODESKIN_ASSIGN_OR_RETURN(std::span<std::byte> inputs, dispatcher_.beginFrame());
  if (!frame.bones.empty()) std::memcpy(inputs.data(), frame.bones.data(), frame.bones.size_bytes());
  if (dual_quaternion_ && !frame.bones.empty()) {
    toGpuDualQuaternions(frame.bones, dual_quats_);
    std::memcpy(inputs.data() + dual_quat_offset_, dual_quats_.data(), dual_quats_.size() * sizeof(gpu::DualQuat));
  }
  const std::uint32_t groups = (vertex_count_ + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize;
  return dispatcher_.submitFrame(&push_constants_, groups);
}

Status GpuLbs::wait() { return dispatcher_.wait(); }

Status GpuLbs::run(const GpuLbsFrame& frame) {
  ODESKIN_TRY(submit(frame));
  return wait();
}

Status GpuLbs::readPositions(std::span<gpu::Float4> out_positions) {
  if (out_positions.size() != vertex_count_) {
    return invalidArgument("lbs gpu: out_positions has " + std::to_string(out_positions.size()) +
                           " entries, expected " + std::to_string(vertex_count_));
  }
  ODESKIN_TRY(wait());
  return vk::downloadSpan(*device_, out_positions_, out_positions);
}

}  // namespace odeskin
