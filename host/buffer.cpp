// SPDX-License-Identifier: MIT
#include "buffer.hpp"

#include <cstring>
#include <string>
#include <utility>

#include "fault_injection.hpp"
#include "vk_status.hpp"

namespace odeskin::vk {

namespace {

Status checkRange(const char* who, VkDeviceSize size, std::size_t bytes, VkDeviceSize offset) {
  if (offset > size || bytes > size - offset) {
    return invalidArgument(std::string(who) + ": " + std::to_string(bytes) + " bytes at offset " +
                           std::to_string(offset) + " exceed the buffer size " + std::to_string(size));
  }
  return okStatus();
}

// The copy of `region` from `src` into a host-read buffer, ordered after earlier shader and transfer
// writes and made visible to the host once the submission's fence is waited on.
void recordCopyToHost(VkCommandBuffer cmd, VkBuffer src, VkBuffer dst, const VkBufferCopy& region) {
  VkMemoryBarrier before{};
  before.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  before.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, nullptr, 0, nullptr);
  vkCmdCopyBuffer(cmd, src, dst, 1, &region);
  VkMemoryBarrier after{};
  after.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  after.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &after, 0, nullptr, 0,
                       nullptr);
}

}  // namespace

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
  ODESKIN_TRY(checkRange("Buffer::upload", size_, bytes.size(), offset));
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
  // Vertex input is a stage of graphics queues only (a compute-only family refuses the barrier).
  const bool graphics = (device.queueFlags() & VK_QUEUE_GRAPHICS_BIT) != 0;
  return device.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdCopyBuffer(cmd, staging.handle(), dst, 1, &region);
    // Make the copy visible to every later shader read, copy, or vertex and index fetch (the
    // renderer's buffers come this way) on this queue: the fence wait orders later submissions but
    // makes no write visible to them.
    VkMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
    VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    if (graphics) {
      barrier.dstAccessMask |= VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT;
      stages |= VK_PIPELINE_STAGE_VERTEX_INPUT_BIT;
    }
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  });
}

Status Buffer::download(const Device& device, std::span<std::byte> out, VkDeviceSize offset) const {
  ODESKIN_TRY(checkRange("Buffer::download", size_, out.size(), offset));
  if (out.empty()) return okStatus();
  if (readsInPlace()) {
    std::memcpy(out.data(), mapped_ + offset, out.size());
    return okStatus();
  }
  // A stage for this one read: what a caller reading every frame keeps instead.
  ODESKIN_ASSIGN_OR_RETURN(ReadbackStage stage, ReadbackStage::create(device, out.size()));
  return stage.download(device, *this, out, offset);
}

Result<ReadbackStage> ReadbackStage::create(const Device& device, VkDeviceSize capacity) {
  ReadbackStage stage;
  ODESKIN_ASSIGN_OR_RETURN(stage.staging_, Buffer::create(device, capacity, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                          MemoryUse::kHostReadback));
  ODESKIN_ASSIGN_OR_RETURN(stage.pool_, device.createCommandPool(VK_COMMAND_POOL_CREATE_TRANSIENT_BIT));
  ODESKIN_ASSIGN_OR_RETURN(stage.cmd_, device.allocateCommandBuffer(stage.pool_.get()));
  ODESKIN_ASSIGN_OR_RETURN(stage.fence_, device.createFence());
  return stage;
}

Status ReadbackStage::download(const Device& device, const Buffer& buffer, std::span<std::byte> out,
                               VkDeviceSize offset) {
  ODESKIN_TRY(checkRange("ReadbackStage::download", buffer.size(), out.size(), offset));
  if (out.empty()) return okStatus();
  if (buffer.readsInPlace()) {
    std::memcpy(out.data(), buffer.mapped() + offset, out.size());
    return okStatus();
  }
  if (out.size() > capacity()) {
    return invalidArgument("ReadbackStage::download: " + std::to_string(out.size()) + " bytes exceed its capacity of " +
                           std::to_string(capacity()));
  }
  ODESKIN_VK_TRY(vkResetCommandPool(device.handle(), pool_.get(), 0));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ODESKIN_VK_TRY(vkBeginCommandBuffer(cmd_, &begin));
  recordCopyToHost(cmd_, buffer.handle(), staging_.handle(), VkBufferCopy{offset, 0, out.size()});
  ODESKIN_VK_TRY(vkEndCommandBuffer(cmd_));
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  VkFence fence = fence_.get();
  ODESKIN_VK_TRY(vkResetFences(device.handle(), 1, &fence));
  ODESKIN_TRY(device.submit(submit, fence));
  ODESKIN_VK_TRY(vkWaitForFences(device.handle(), 1, &fence, VK_TRUE, UINT64_MAX));
  std::memcpy(out.data(), staging_.mapped(), out.size());
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
