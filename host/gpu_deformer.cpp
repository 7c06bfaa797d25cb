// SPDX-License-Identifier: MIT
#include "gpu_deformer.hpp"

#include <cstring>
#include <string>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "shaders/fourier_deform.spv.h"

namespace odeskin {
namespace {

template <typename T>
std::span<const std::byte> bytesOf(const std::vector<T>& v) {
  return std::as_bytes(std::span<const T>(v));
}

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
  return alignment == 0 ? value : (value + alignment - 1) / alignment * alignment;
}

// Per-frame slices are at least 16 bytes so bone_count = 0 or no modes still bind a valid range.
VkDeviceSize sliceBytes(std::size_t bytes) { return bytes < 16 ? 16 : bytes; }

}  // namespace

Result<GpuDeformer> GpuDeformer::create(const vk::Device& device, const PackedDeformData& data) {
  // The CPU job's own checks on the packed arrays, so both paths accept exactly the same data.
  {
    std::vector<gpu::BoneMatrix> bones(data.bone_count);
    std::vector<gpu::ModeBasis> basis(ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes}));
    std::vector<gpu::Float4> out(data.vertex_count);
    FourierDeformFastJob job;
    job.data = &data;
    job.segment = 0;
    job.bones = bones;
    job.basis = basis;
    job.out_positions = out;
    ODESKIN_TRY(job.validate());
  }

  GpuDeformer deformer;
  deformer.device_ = &device;
  deformer.vertex_count_ = data.vertex_count;
  deformer.segment_count_ = data.segment_count;
  deformer.bone_count_ = data.bone_count;
  deformer.basis_count_ = ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes});
  for (std::uint32_t s = 0; s < data.segment_count; ++s) {
    deformer.push_constants_.push_back(deformPushConstants(data, s));
  }

  // Uploaded once, read every frame: device-local (mapped on lavapipe/ReBAR, staged elsewhere).
  struct Array {
    std::uint32_t binding;
    std::span<const std::byte> bytes;
  };
  const Array arrays[] = {
      {ODESKIN_BINDING_REST_POSITIONS, bytesOf(data.rest_positions)},
      {ODESKIN_BINDING_VERTEX_BINDINGS, bytesOf(data.bindings)},
      {ODESKIN_BINDING_SEGMENT_VERTICES, bytesOf(data.segment_vertices)},
      {ODESKIN_BINDING_REMAINDERS, bytesOf(data.remainders)},
      {ODESKIN_BINDING_CURVE_MATERIALS, bytesOf(data.curve_materials)},
      {ODESKIN_BINDING_COEFFICIENTS, bytesOf(data.coefficients)},
      {ODESKIN_BINDING_RATES, bytesOf(data.rates)},
      {ODESKIN_BINDING_INFLUENCE_OFFSETS, bytesOf(data.influence_offsets)},
      {ODESKIN_BINDING_INFLUENCES, bytesOf(data.influences)},
  };
  std::vector<vk::StaticBinding> statics;
  for (const Array& array : arrays) {
    ODESKIN_ASSIGN_OR_RETURN(vk::Buffer buffer, vk::createStorageBuffer(device, array.bytes));
    statics.push_back({array.binding, buffer.handle()});
    deformer.inputs_.push_back(std::move(buffer));
  }
  // The output doubles as a vertex buffer and a copy source (readback on non-mappable memory).
  const std::size_t out_bytes = static_cast<std::size_t>(data.vertex_count) * sizeof(gpu::Float4);
  ODESKIN_ASSIGN_OR_RETURN(deformer.out_positions_,
                           vk::Buffer::create(device, sliceBytes(out_bytes), vk::kOutputBufferUsage));
  statics.push_back({ODESKIN_BINDING_OUT_POSITIONS, deformer.out_positions_.handle()});

  // Per-frame buffer: bones, the basis, then the bones' dual quaternions, each at the next offset
  // the device allows for a binding. The dual quaternion slice is bound (and small) in either
  // skinning mode, so one pipeline layout serves both; it is only written for dual quaternions.
  const VkDeviceSize alignment = device.limits().minStorageBufferOffsetAlignment;
  const VkDeviceSize bones_bytes = sliceBytes(static_cast<std::size_t>(data.bone_count) * sizeof(gpu::BoneMatrix));
  const VkDeviceSize basis_bytes = sliceBytes(deformer.basis_count_ * sizeof(gpu::ModeBasis));
  const VkDeviceSize dual_quat_bytes = sliceBytes(static_cast<std::size_t>(data.bone_count) * sizeof(gpu::DualQuat));
  deformer.basis_offset_ = alignUp(bones_bytes, alignment);
  deformer.dual_quat_offset_ = alignUp(deformer.basis_offset_ + basis_bytes, alignment);
  deformer.dual_quaternion_ = data.skinning == SkinningMode::kDualQuaternion;
  if (deformer.dual_quaternion_) deformer.dual_quats_.resize(data.bone_count);
  const vk::FrameBinding frame_bindings[] = {
      {ODESKIN_BINDING_BONES, 0, bones_bytes},
      {ODESKIN_BINDING_MODE_BASIS, deformer.basis_offset_, basis_bytes},
      {ODESKIN_BINDING_BONE_DUAL_QUATS, deformer.dual_quat_offset_, dual_quat_bytes},
  };
  if (bones_bytes > device.limits().maxStorageBufferRange || dual_quat_bytes > device.limits().maxStorageBufferRange) {
    return unavailable("fourier deform gpu: " + std::to_string(data.bone_count) +
                       " bones exceed maxStorageBufferRange");
  }

  vk::ComputeDispatcherDesc desc;
  desc.spirv = kFourierDeformSpirv;
  desc.static_bindings = statics;
  desc.frame_bindings = frame_bindings;
  desc.frame_bytes = deformer.dual_quat_offset_ + dual_quat_bytes;
  desc.push_constant_bytes = sizeof(gpu::DeformPushConstants);
  desc.frames_in_flight = 2;
  ODESKIN_ASSIGN_OR_RETURN(deformer.dispatcher_, vk::ComputeDispatcher::create(device, desc));
  return deformer;
}

Status GpuDeformer::validate(const GpuDeformFrame& frame) const {
  // Same checks and messages as FourierDeformFastJob::validate, per-frame fields only (the packed
  // arrays were checked by create()).
  if (frame.segment >= segment_count_) {
    return invalidArgument("fourier deform gpu: segment " + std::to_string(frame.segment) + " of " +
                           std::to_string(segment_count_));
  }
  if (frame.bones.size() != bone_count_) {
    return invalidArgument("fourier deform gpu: bones has " + std::to_string(frame.bones.size()) +
                           " entries, expected " + std::to_string(bone_count_));
  }
  if (frame.basis.size() != basis_count_) {
    return invalidArgument("fourier deform gpu: basis has " + std::to_string(frame.basis.size()) +
                           " entries, expected material_count x (N+1) + 1 = " + std::to_string(basis_count_));
  }
  return okStatus();
}

Status GpuDeformer::submit(const GpuDeformFrame& frame) {
  ODESKIN_TRY(validate(frame));
  if (vertex_count_ == 0) return okStatus();
  ODESKIN_ASSIGN_OR_RETURN(std::span<std::byte> inputs, dispatcher_.beginFrame());
  // Plain copies into coherent mapped memory; the queue submit publishes them to the device.
  if (!frame.bones.empty()) std::memcpy(inputs.data(), frame.bones.data(), frame.bones.size_bytes());
  if (!frame.basis.empty()) {
    std::memcpy(inputs.data() + basis_offset_, frame.basis.data(), frame.basis.size_bytes());
  }
  if (dual_quaternion_ && !frame.bones.empty()) {
    toGpuDualQuaternions(frame.bones, dual_quats_);
    std::memcpy(inputs.data() + dual_quat_offset_, dual_quats_.data(), dual_quats_.size() * sizeof(gpu::DualQuat));
  }
  const std::uint32_t groups = (vertex_count_ + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize;
  return dispatcher_.submitFrame(&push_constants_[frame.segment], groups);
}

Status GpuDeformer::wait() { return dispatcher_.wait(); }

Status GpuDeformer::run(const GpuDeformFrame& frame) {
  ODESKIN_TRY(submit(frame));
  return wait();
}

Status GpuDeformer::readPositions(std::span<gpu::Float4> out_positions) {
  if (out_positions.size() != vertex_count_) {
    return invalidArgument("fourier deform gpu: out_positions has " + std::to_string(out_positions.size()) +
                           " entries, expected " + std::to_string(vertex_count_));
  }
  ODESKIN_TRY(wait());
  return vk::downloadSpan(*device_, out_positions_, out_positions);
}

OutputBarrier GpuDeformer::outputBarrier() const {
  OutputBarrier result;
  VkBufferMemoryBarrier& b = result.barrier;
  b.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
  b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.buffer = out_positions_.handle();
  b.offset = 0;
  b.size = VK_WHOLE_SIZE;
  return result;
}

}  // namespace odeskin
