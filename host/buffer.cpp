// SPDX-License-Identifier: MIT
#include "buffer.hpp"

#include <cstring>
#include <string>
#include <utility>

#include "fault_injection.hpp"
#include "vk_status.hpp"

namespace odeskin::vk {

Result<Buffer> Buffer::create(const Device& device, VkDeviceSize size_bytes, VkBufferUsageFlags usage,
                              MemoryUse use) {
  if (size_bytes == 0) return invalidArgument("Buffer::create: size_bytes must be > 0");
  Buffer buffer;
  buffer.device_ = device.handle();
  buffer.size_ = size_bytes;
  // Every buffer can be a copy destination (staged upload) and source (staged readback): whether a
  // mapped one is read directly depends on the memory type the device gives it.
  usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;

  // Exclusive: a single queue family touches it.
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = size_bytes;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer handle = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateBuffer(device.handle(), &info, nullptr, &handle));
  buffer.buffer_ = UniqueBuffer(device.handle(), handle);

  // The memory type: mappable device-local first (no staging copies at all), then by use.
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device.handle(), handle, &requirements);
  constexpr VkMemoryPropertyFlags kHost = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  constexpr VkMemoryPropertyFlags kLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  const bool host = use == MemoryUse::kHostVisible || use == MemoryUse::kHostReadback;
  VkMemoryPropertyFlags required = host ? kHost : kLocal;
  VkMemoryPropertyFlags preferred = use == MemoryUse::kDeviceLocalStaged ? kLocal
                                    : use == MemoryUse::kHostReadback  ? (kHost | VK_MEMORY_PROPERTY_HOST_CACHED_BIT)
                                                                       : (kHost | kLocal);
  Result<std::uint32_t> type = device.findMemoryType(requirements.memoryTypeBits, required, preferred);
  if (!type.ok() && !host) {
    // Some devices expose no DEVICE_LOCAL type for a given buffer; any type will still work.
    type = device.findMemoryType(requirements.memoryTypeBits, 0, preferred);
  }
  if (!type.ok()) return type.status();

  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = *type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult allocated = injectedResult(VkFault::kOutOfMemory);
  if (allocated == VK_SUCCESS) allocated = vkAllocateMemory(device.handle(), &alloc, nullptr, &memory);
  ODESKIN_TRY(vkStatus(allocated, "vkAllocateMemory"));
  buffer.memory_ = UniqueMemory(device.handle(), memory);
  buffer.allocated_ = requirements.size;
  ODESKIN_VK_TRY(vkBindBufferMemory(device.handle(), handle, memory, 0));

  // Persistently mapped: coherent memory needs no flush, and mapping once costs nothing per frame.
  VkMemoryPropertyFlags flags = device.memoryProperties().memoryTypes[*type].propertyFlags;
  buffer.memory_flags_ = flags;
  if (use != MemoryUse::kDeviceLocalStaged && (flags & kHost) == kHost) {
    void* pointer = nullptr;
    ODESKIN_VK_TRY(vkMapMemory(device.handle(), memory, 0, VK_WHOLE_SIZE, 0, &pointer));
    buffer.mapped_ = static_cast<std::byte*>(pointer);
  }
  return buffer;
}

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    destroy();
    buffer_ = std::move(other.buffer_);
    memory_ = std::move(other.memory_);
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    allocated_ = std::exchange(other.allocated_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
    memory_flags_ = std::exchange(other.memory_flags_, 0);
  }
  return *this;
}

Buffer::~Buffer() { destroy(); }

void Buffer::destroy() {
  // Freeing memory unmaps it implicitly; the buffer must go before its memory.
  buffer_.reset();
  memory_.reset();
  mapped_ = nullptr;
}

Status Buffer::upload(const Device& device, std::span<const std::byte> bytes, VkDeviceSize offset) {
  if (offset > size_ || bytes.size() > size_ - offset) {
    return invalidArgument("Buffer::upload: " + std::to_string(bytes.size()) + " bytes at offset " +
                           std::to_string(offset) + " exceed the buffer size " + std::to_string(size_));
  }
  if (bytes.empty()) return okStatus();
  if (mapped_ != nullptr) {
    std::memcpy(mapped_ + offset, bytes.data(), bytes.size());
    return okStatus();
  }
  // Staging: a host-visible copy, then a transfer into this buffer, waited for before returning.
  ODESKIN_ASSIGN_OR_RETURN(Buffer staging, create(device, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                  MemoryUse::kHostVisible));
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());
  VkBufferCopy region{0, offset, bytes.size()};
  VkBuffer dst = handle();
  return device.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdCopyBuffer(cmd, staging.handle(), dst, 1, &region);
    // Make the copy visible to every later shader read or copy on this queue.
    VkMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                         &barrier, 0, nullptr, 0, nullptr);
  });
}

Status Buffer::download(const Device& device, std::span<std::byte> out, VkDeviceSize offset) const {
  if (offset > size_ || out.size() > size_ - offset) {
    return invalidArgument("Buffer::download: " + std::to_string(out.size()) + " bytes at offset " +
                           std::to_string(offset) + " exceed the buffer size " + std::to_string(size_));
  }
  if (out.empty()) return okStatus();
  if (mapped_ != nullptr && hostReadsDirectly(memory_flags_)) {
    std::memcpy(out.data(), mapped_ + offset, out.size());
    return okStatus();
  }
  ODESKIN_ASSIGN_OR_RETURN(Buffer staging, create(device, out.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                  MemoryUse::kHostReadback));
  VkBufferCopy region{offset, 0, out.size()};
  VkBuffer src = handle();
  ODESKIN_TRY(device.submitAndWait([&](VkCommandBuffer cmd) {
    // Earlier shader writes must land before the copy reads them.
    VkMemoryBarrier before{};
    before.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    before.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, nullptr, 0, nullptr);
    vkCmdCopyBuffer(cmd, src, staging.handle(), 1, &region);
    // The host reads the staging copy after the fence: make the transfer write host-visible.
    VkMemoryBarrier after{};
    after.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    after.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &after, 0,
                         nullptr, 0, nullptr);
  }));
  std::memcpy(out.data(), staging.mapped(), out.size());
  return okStatus();
}

Result<Buffer> createStorageBuffer(const Device& device, std::span<const std::byte> bytes,
                                   VkBufferUsageFlags extra_usage, MemoryUse use) {
  // 16 bytes: the smallest std430 element we bind (Float4); a zero-sized VkBuffer is invalid.
  VkDeviceSize size = bytes.size() < 16 ? 16 : bytes.size();
  if (size > device.limits().maxStorageBufferRange) {
    return unavailable("a " + std::to_string(size) + "-byte storage buffer exceeds maxStorageBufferRange (" +
                       std::to_string(device.limits().maxStorageBufferRange) + " bytes) of " + device.name());
  }
  ODESKIN_ASSIGN_OR_RETURN(Buffer buffer,
                           Buffer::create(device, size, kShaderInputUsage | extra_usage, use));
  ODESKIN_TRY(buffer.upload(device, bytes));
  return buffer;
}

}  // namespace odeskin::vk
