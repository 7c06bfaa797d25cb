// SPDX-License-Identifier: MIT
// GPU dispatcher of FourierDeformFastJob (shaders/fourier_deform.comp; thesis Eq 6.30 corrected,
// MATH.md 5.6): the packed data is uploaded once, then each frame writes the same per-frame fields
// as the CPU job (segment, bones, basis) into a double-buffered mapped buffer and runs ONE dispatch
// of ceil(V / 64) workgroups into an output buffer a renderer can bind as vertex input. With
// data.skinning = kDualQuaternion each frame also converts the bones to dual quaternions on the
// host (toGpuDualQuaternions, as FourierDeformFastJob does) and writes them beside the bones.
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

namespace odeskin {

// The per-frame fields of FourierDeformFastJob, same names and contracts.
struct GpuDeformFrame {
  std::uint32_t segment = 0;                // < data.segment_count
  std::span<const gpu::BoneMatrix> bones;   // data.bone_count, required: M_b(tau)
  std::span<const gpu::ModeBasis> basis;    // data.material_count * (N+1), required
};

// Barrier a renderer records before reading outputBuffer() as vertex input (same queue, later
// submission): compute-shader writes made visible to vertex attribute fetch.
struct OutputBarrier {
  VkPipelineStageFlags src_stage = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  VkPipelineStageFlags dst_stage = VK_PIPELINE_STAGE_VERTEX_INPUT_BIT;
  VkBufferMemoryBarrier barrier{};
};

class GpuDeformer {
 public:
  // Uploads every array of `data` (gpu_layout.h bindings 0-8) once; `data` may be freed afterwards.
  // kInvalidArgument as FourierDeformFastJob::validate for inconsistent packed data (checked with
  // segment 0, so segment_count must be >= 1); kUnavailable when an array exceeds
  // maxStorageBufferRange; kDeviceError from the driver.
  static Result<GpuDeformer> create(const vk::Device& device, const PackedDeformData& data);

  // kInvalidArgument naming the field, as FourierDeformFastJob::validate.
  Status validate(const GpuDeformFrame& frame) const;
  // submit() then wait(): the frame's positions are in outputBuffer() when it returns.
  Status run(const GpuDeformFrame& frame);
  // Validates, waits for the frame that last used the same input slot (two frames back), writes
  // the inputs, records and submits. No allocation. V = 0 validates and submits nothing.
  Status submit(const GpuDeformFrame& frame);
  // Waits for every submitted frame and updates lastGpuSeconds().
  Status wait();

  // Copies the last completed frame's positions (xyz, w = 1) into `out_positions`, whose size
  // must be vertex_count (kInvalidArgument otherwise). Waits for submitted frames first.
  Status readPositions(std::span<gpu::Float4> out_positions);

  VkBuffer outputBuffer() const { return out_positions_.handle(); }
  VkDeviceSize outputBytes() const { return static_cast<VkDeviceSize>(vertex_count_) * sizeof(gpu::Float4); }
  OutputBarrier outputBarrier() const;
  // GPU time of the last completed dispatch from timestamp queries, in seconds (0 if unsupported).
  double lastGpuSeconds() const { return dispatcher_.lastGpuSeconds(); }
  std::uint32_t vertexCount() const { return vertex_count_; }

 private:
  GpuDeformer() = default;

  const vk::Device* device_ = nullptr;
  std::uint32_t vertex_count_ = 0;
  std::uint32_t segment_count_ = 0;
  std::uint32_t bone_count_ = 0;
  std::size_t basis_count_ = 0;
  VkDeviceSize basis_offset_ = 0;  // of the basis slice inside each per-frame buffer
  VkDeviceSize dual_quat_offset_ = 0;  // of the bone dual quaternion slice
  bool dual_quaternion_ = false;       // data.skinning == kDualQuaternion
  std::vector<gpu::DualQuat> dual_quats_;  // bone_count when dual_quaternion_: per-frame scratch
  std::vector<gpu::DeformPushConstants> push_constants_;  // one per segment, computed once
  // The dispatcher is declared last so it is destroyed first: it waits for in-flight frames
  // before the buffers they read go away.
  std::vector<vk::Buffer> inputs_;
  vk::Buffer out_positions_;
  vk::ComputeDispatcher dispatcher_;
};

}  // namespace odeskin
