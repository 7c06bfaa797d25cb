// SPDX-License-Identifier: MIT
// GPU dispatcher of FourierDeformFastJob (shaders/fourier_deform.comp; thesis Eq 6.30 corrected,
// MATH.md 5.6): the packed data is uploaded once, then each frame writes the same per-frame fields
// as the CPU job (segment, bones, basis) into a double-buffered mapped buffer and records two
// dispatches in one command buffer: fold_series.comp folds the basis into the segment's curve
// coefficients (C x (2N + 2) invocations), then ceil(V / 64) workgroups deform every vertex into an
// output buffer a renderer can bind as vertex input. With
// data.skinning = kDualQuaternion each frame also converts the bones to dual quaternions on the
// host (toGpuDualQuaternions, as FourierDeformFastJob does) and writes them beside the bones. The
// frame ring, per-frame writer and readback are SingleMeshDispatch's, shared with GpuLbs.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "buffer.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "output_barrier.hpp"
#include "single_mesh_dispatch.hpp"

namespace odeskin {

// The per-frame fields of FourierDeformFastJob, same names and contracts.
struct GpuDeformFrame {
  std::uint32_t segment = 0;                // < data.segment_count
  std::span<const gpu::BoneMatrix> bones;   // data.bone_count, required: M_b(tau)
  std::span<const gpu::ModeBasis> basis;    // data.material_count * (N+1), required
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
  Status wait() { return dispatch_.wait(); }

  // Copies the last completed frame's positions (xyz, w = 1) into `out_positions`, whose size
  // must be vertex_count (kInvalidArgument otherwise). Waits for submitted frames first.
  Status readPositions(std::span<gpu::Float4> out_positions) { return dispatch_.readPositions(out_positions); }

  VkBuffer outputBuffer() const { return dispatch_.outputBuffer(); }
  VkDeviceSize outputBytes() const { return static_cast<VkDeviceSize>(vertexCount()) * sizeof(gpu::Float4); }
  OutputBarrier outputBarrier() const { return dispatch_.outputBarrier(); }
  // GPU time of the last completed dispatch from timestamp queries, in seconds (0 if unsupported).
  double lastGpuSeconds() const { return dispatch_.lastGpuSeconds(); }
  std::uint32_t vertexCount() const { return dispatch_.vertexCount(); }

 private:
  GpuDeformer() = default;

  std::uint32_t segment_count_ = 0;
  std::uint32_t bone_count_ = 0;
  std::size_t basis_count_ = 0;
  std::vector<gpu::DeformPushConstants> push_constants_;  // one per segment, computed once
  std::vector<vk::Buffer> inputs_;
  // Declared last so it is destroyed first: it waits for in-flight frames before the buffers they
  // read go away.
  SingleMeshDispatch dispatch_;
};

}  // namespace odeskin
