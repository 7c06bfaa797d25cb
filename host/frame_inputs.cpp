// SPDX-License-Identifier: MIT
#include "frame_inputs.hpp"

#include <algorithm>
#include <string>

namespace odeskin::vk {

// Slices are bound as storage or as texel buffers; both limits are powers of two, so the larger
// one satisfies both.
FrameInputLayout::FrameInputLayout(const Device& device)
    : alignment_(std::max(device.limits().minStorageBufferOffsetAlignment, device.limits().minTexelBufferOffsetAlignment)),
      max_range_(device.limits().maxStorageBufferRange) {}

VkDeviceSize FrameInputLayout::add(std::uint32_t binding, std::size_t bytes) {
  const VkDeviceSize offset = alignment_ == 0 ? total_ : (total_ + alignment_ - 1) / alignment_ * alignment_;
  const VkDeviceSize size = bytes < 16 ? 16 : bytes;
  bindings_.push_back(FrameBinding{binding, offset, size});
  total_ = offset + size;
  return offset;
}

Status FrameInputLayout::checkLimits(const char* what) const {
  for (const FrameBinding& b : bindings_) {
    if (b.size > max_range_) {
      return unavailable(std::string(what) + ": the " + std::to_string(b.size) + "-byte per-frame slice of binding " +
                         std::to_string(b.binding) + " exceeds maxStorageBufferRange (" + std::to_string(max_range_) +
                         " bytes)");
    }
  }
  return okStatus();
}

BonePaletteWriter BonePaletteWriter::plan(FrameInputLayout& layout, std::uint32_t bones_binding,
                                          std::uint32_t dual_quat_binding, std::size_t matrices,
                                          SkinningMode skinning) {
  BonePaletteWriter writer;
  writer.dual_quaternion_ = skinning == SkinningMode::kDualQuaternion;
  writer.bones_offset_ = layout.add(bones_binding, matrices * sizeof(gpu::BoneMatrix));
  writer.dual_quat_offset_ = layout.add(dual_quat_binding, writer.dual_quaternion_ ? matrices * sizeof(gpu::DualQuat) : 0);
  return writer;
}

void BonePaletteWriter::write(std::span<std::byte> frame, std::span<const gpu::BoneMatrix> bones,
                              std::size_t first) const {
  writeSlice(frame, bones_offset_ + first * sizeof(gpu::BoneMatrix), bones);
  if (!dual_quaternion_) return;
  std::byte* out = frame.data() + dual_quat_offset_ + first * sizeof(gpu::DualQuat);
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const gpu::DualQuat q = toGpuDualQuaternion(bones[b]);
    std::memcpy(out + b * sizeof(gpu::DualQuat), &q, sizeof(q));
  }
}

}  // namespace odeskin::vk
