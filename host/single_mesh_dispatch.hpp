// SPDX-License-Identifier: MIT
// What GpuDeformer and GpuLbs share: one mesh's output buffer (storage, vertex and copy source),
// a ComputeDispatcher whose per-frame inputs are a bone palette and optionally a time basis
// (BonePaletteWriter), and submit / wait / readPositions. The two classes keep their own checks,
// uploads and push constants.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <vulkan/vulkan.h>

#include "buffer.hpp"
#include "compute_dispatcher.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "frame_inputs.hpp"
#include "output_barrier.hpp"

namespace odeskin {

struct SingleMeshDispatchDesc {
  std::string name;                             // "fourier deform gpu": prefixes every message
  std::span<const std::uint32_t> spirv;         // gpu_layout.h bindings, read as texel buffers
  std::span<const std::uint32_t> storage_spirv; // the same shader reading storage buffers (shader_inputs.hpp)
  std::uint32_t vertex_count = 0;
  std::uint32_t bone_count = 0;
  SkinningMode skinning = SkinningMode::kLinear;
  std::size_t basis_count = 0;                  // 0: the shader reads no time basis
  std::span<const vk::StaticBinding> statics;   // uploaded arrays; the output is added here
  std::uint32_t push_constant_bytes = 0;
  // With modes and curves (basis_count > 0): fold_series.comp folds the frame's basis into the
  // curves' coefficients (statics: materials, coefficients, rates) before the main dispatch.
  bool fold_series = false;
  std::uint32_t modes = 0;
  std::uint32_t curve_count = 0;
};

class SingleMeshDispatch {
 public:
  // `device` must outlive the object and stay where it is. kUnavailable when a per-frame slice
  // exceeds maxStorageBufferRange; kInvalidArgument for a bad ODESKIN_SHADER_INPUTS; kDeviceError
  // from the driver.
  static Result<SingleMeshDispatch> create(const vk::Device& device, const SingleMeshDispatchDesc& desc);

  // Writes `bones` and `basis` (sizes checked by the caller) into the next frame slot, waiting for
  // the frame that used it last, and submits ceil(V / 64) workgroups with `push`. V = 0: nothing.
  // With fold_series, the fold of segment `segment` (its rates if `use_rates`) runs first.
  Status submit(std::span<const gpu::BoneMatrix> bones, std::span<const gpu::ModeBasis> basis, const void* push,
                std::uint32_t segment = 0, bool use_rates = false);
  Status wait() { return dispatcher_.wait(); }
  // kInvalidArgument when `out_positions` is not vertex_count long; waits for submitted frames.
  Status readPositions(std::span<gpu::Float4> out_positions);

  VkBuffer outputBuffer() const { return out_positions_.handle(); }
  OutputBarrier outputBarrier() const;
  double lastGpuSeconds() const { return dispatcher_.lastGpuSeconds(); }
  std::uint32_t vertexCount() const { return vertex_count_; }

 private:
  const vk::Device* device_ = nullptr;
  std::string name_;
  std::uint32_t vertex_count_ = 0;
  VkDeviceSize basis_offset_ = 0;
  VkDeviceSize record_offset_ = 0;       // fold_series: the frame's InstanceRecord
  gpu::FoldPushConstants fold_push_{};
  std::uint32_t fold_groups_ = 0;        // 0: no fold pass
  vk::Buffer folded_;                    // fold_series: C x M Float4, shared by the frames (see submit)
  vk::BonePaletteWriter palettes_;
  vk::Buffer out_positions_;
  vk::ComputeDispatcher dispatcher_;  // last: destroyed first, after waiting for its frames
};

}  // namespace odeskin
