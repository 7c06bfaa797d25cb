// SPDX-License-Identifier: MIT
// GPU dispatcher of LbsFastJob (shaders/lbs.comp; thesis Eq 6.1): plain skinning of the same
// packed data, the baseline of every speed ratio; linear blend, or dual-quaternion skinning when
// data.skinning says so (bones converted per frame on the host, as in GpuDeformer). The frame
// ring, per-frame writer and readback are SingleMeshDispatch's, shared with GpuDeformer.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "buffer.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "gpu_deformer.hpp"
#include "single_mesh_dispatch.hpp"

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
  Status wait() { return dispatch_.wait(); }
  Status readPositions(std::span<gpu::Float4> out_positions) { return dispatch_.readPositions(out_positions); }

  VkBuffer outputBuffer() const { return dispatch_.outputBuffer(); }
  OutputBarrier outputBarrier() const { return dispatch_.outputBarrier(); }
  double lastGpuSeconds() const { return dispatch_.lastGpuSeconds(); }
  std::uint32_t vertexCount() const { return dispatch_.vertexCount(); }

 private:
  GpuLbs() = default;

  std::uint32_t bone_count_ = 0;
  gpu::DeformPushConstants push_constants_{};
  std::vector<vk::Buffer> inputs_;
  SingleMeshDispatch dispatch_;  // last: destroyed first, after waiting for its frames
};

}  // namespace odeskin
