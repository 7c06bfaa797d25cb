// SPDX-License-Identifier: MIT
// GPU dispatcher of LbsFastJob (shaders/lbs.comp; thesis Eq 6.1): plain skinning of the same
// packed data, the baseline of every speed ratio; linear blend, or dual-quaternion skinning when
// data.skinning says so (bones converted per frame on the host, as in GpuDeformer). Same frame
// ring as GpuDeformer.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "buffer.hpp"
#include "compute_dispatcher.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "gpu_deformer.hpp"

namespace odeskin {

// The per-frame field of LbsFastJob.
struct GpuLbsFrame {
  std::span<const gpu::BoneMatrix> bones;  // data.bone_count, required
};

class GpuLbs {
 public:
  // Uploads rest positions and influences (bindings 0, 7, 8) once. kInvalidArgument as
  // LbsFastJob::validate; kUnavailable / kDeviceError as GpuDeformer::create. `device` must
  // outlive the object and stay where it is.
  static Result<GpuLbs> create(const vk::Device& device, const PackedDeformData& data);

  Status validate(const GpuLbsFrame& frame) const;
  Status run(const GpuLbsFrame& frame);
  Status submit(const GpuLbsFrame& frame);
  Status wait();
  Status readPositions(std::span<gpu::Float4> out_positions);

  VkBuffer outputBuffer() const { return out_positions_.handle(); }
  double lastGpuSeconds() const { return dispatcher_.lastGpuSeconds(); }
  std::uint32_t vertexCount() const { return vertex_count_; }

 private:
  GpuLbs() = default;

  const vk::Device* device_ = nullptr;
  std::uint32_t vertex_count_ = 0;
  std::uint32_t bone_count_ = 0;
  gpu::DeformPushConstants push_constants_{};
  VkDeviceSize dual_quat_offset_ = 0;      // of the bone dual quaternion slice in the frame buffer
  bool dual_quaternion_ = false;           // data.skinning == kDualQuaternion
  std::vector<gpu::DualQuat> dual_quats_;  // bone_count when dual_quaternion_: per-frame scratch
  std::vector<vk::Buffer> inputs_;
  vk::Buffer out_positions_;
  vk::ComputeDispatcher dispatcher_;  // last: destroyed first, after waiting for its frames
};

}  // namespace odeskin
