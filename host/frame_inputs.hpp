// SPDX-License-Identifier: MIT
// The per-frame input writer shared by GpuDeformer, GpuLbs and VulkanRuntime: slices of a frame
// slot's mapped buffer, each bound to one storage binding, and the bone palettes every skinning
// shader reads (BoneMatrix rows, plus their unit dual quaternions for dual-quaternion skinning,
// computed on the host as FourierDeformFastJob does).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "compute_dispatcher.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "engine/kernels/packed_deform.hpp"

namespace odeskin::vk {

class FrameInputLayout {
 public:
  explicit FrameInputLayout(const Device& device);

  // Appends a slice of `bytes` (rounded up to 16, so empty arrays still bind a valid range) at the
  // next offset the device allows for a binding; returns that offset.
  VkDeviceSize add(std::uint32_t binding, std::size_t bytes);
  std::span<const FrameBinding> bindings() const { return bindings_; }
  // Bytes of one slot's buffer.
  VkDeviceSize totalBytes() const { return total_; }
  // kUnavailable, naming `what`, when a slice exceeds maxStorageBufferRange.
  Status checkLimits(const char* what) const;

 private:
  VkDeviceSize alignment_ = 0;
  VkDeviceSize max_range_ = 0;
  VkDeviceSize total_ = 0;
  std::vector<FrameBinding> bindings_;
};

// Copies `values` into the frame's mapped bytes at `offset` (memcpy: mapped memory is raw bytes).
template <typename T>
void writeSlice(std::span<std::byte> frame, VkDeviceSize offset, std::span<const T> values) {
  if (!values.empty()) std::memcpy(frame.data() + offset, values.data(), values.size_bytes());
}

class BonePaletteWriter {
 public:
  BonePaletteWriter() = default;
  // Adds the bone slice (`matrices` BoneMatrix) at `bones_binding` and the dual quaternion slice at
  // `dual_quat_binding` to `layout`. The dual quaternion slice is bound in either skinning mode (one
  // pipeline layout serves both) but is only sized and written for kDualQuaternion.
  static BonePaletteWriter plan(FrameInputLayout& layout, std::uint32_t bones_binding, std::uint32_t dual_quat_binding,
                                std::size_t matrices, SkinningMode skinning);

  // Writes `bones` at matrix index `first` of the frame's slices (and, for dual-quaternion
  // skinning, each one's toGpuDualQuaternion). No allocation.
  void write(std::span<std::byte> frame, std::span<const gpu::BoneMatrix> bones, std::size_t first = 0) const;

 private:
  VkDeviceSize bones_offset_ = 0;
  VkDeviceSize dual_quat_offset_ = 0;
  bool dual_quaternion_ = false;
};

}  // namespace odeskin::vk
