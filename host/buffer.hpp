// SPDX-License-Identifier: MIT
// A VkBuffer with its own VkDeviceMemory. Device-local data is mapped directly when a memory type
// is DEVICE_LOCAL|HOST_VISIBLE|HOST_COHERENT (lavapipe, ReBAR GPUs) and staged otherwise.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "device.hpp"
#include "engine/core/result.hpp"
#include "vk_handle.hpp"

namespace odeskin::vk {

enum class MemoryUse {
  // Read by shaders every frame: device-local; host-mapped when such a type exists, else written
  // and read through a temporary staging buffer.
  kDeviceLocal,
  // As kDeviceLocal but never mapped, always staged: the discrete-GPU path, forced (tests, benches).
  kDeviceLocalStaged,
  // Written by the host every frame and kept mapped (HOST_VISIBLE|HOST_COHERENT required).
  kHostVisible,
  // Written by the device, read by the host: HOST_VISIBLE|HOST_COHERENT, HOST_CACHED preferred. A
  // discrete GPU's device-local mappable (ReBAR) memory is uncached for the CPU: reading a
  // tessellated 1000 x 1000 patch back from it took 652 ms on an H200 (docs/performance.md).
  kHostReadback,
};

// Whether the host reads a mapped buffer of these memory properties at memory speed: only cached
// memory; uncached mappings (ReBAR, write-combined host memory) are written fast and read slowly, so
// download() stages those through kHostReadback memory.
inline bool hostReadsDirectly(VkMemoryPropertyFlags flags) { return (flags & VK_MEMORY_PROPERTY_HOST_CACHED_BIT) != 0; }

// Usage of a buffer a shader reads: as a storage buffer, or as a uniform texel buffer
// (TexelBinding in compute_pipeline.hpp).
inline constexpr VkBufferUsageFlags kShaderInputUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;

// Usage of a buffer a deformer writes, a later pass reads (normals) and a renderer may bind
// directly as vertex input.
inline constexpr VkBufferUsageFlags kOutputBufferUsage = kShaderInputUsage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                                         VK_BUFFER_USAGE_TRANSFER_SRC_BIT;

class Buffer {
 public:
  // `size_bytes` > 0 (a zero-sized VkBuffer is invalid; callers round empty arrays up). Transfer
  // usage is added to every buffer (staged uploads and readbacks). kDeviceError on allocation
  // failure, kUnavailable when no memory type fits.
  static Result<Buffer> create(const Device& device, VkDeviceSize size_bytes, VkBufferUsageFlags usage,
                               MemoryUse use = MemoryUse::kDeviceLocal);

  Buffer() = default;
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer();

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  // Bytes of its memory allocation: size() rounded up as the device requires; 0 for no buffer.
  VkDeviceSize allocatedBytes() const { return allocated_; }
  // Host pointer to the whole buffer when it is mapped, else null.
  std::byte* mapped() const { return mapped_; }
  // Mapped in memory the host reads at memory speed (hostReadsDirectly): download() reads it there.
  bool readsInPlace() const { return mapped_ != nullptr && hostReadsDirectly(memory_flags_); }

  // Copies `bytes` to [offset, offset + bytes.size()): memcpy when mapped, else through a staging
  // buffer and a one-off submit. kInvalidArgument when the range exceeds the buffer. The caller
  // makes sure the GPU is not using the range.
  Status upload(const Device& device, std::span<const std::byte> bytes, VkDeviceSize offset = 0);
  // Copies [offset, offset + out.size()) to `out`; the caller has waited for the writes. Reads the
  // mapping when readsInPlace(), else copies through a one-off ReadbackStage (below).
  Status download(const Device& device, std::span<std::byte> out, VkDeviceSize offset = 0) const;
  VkMemoryPropertyFlags memoryFlags() const { return memory_flags_; }

 private:
  void destroy();

  UniqueBuffer buffer_;   // declared before memory_: destroyed first
  UniqueMemory memory_;
  VkDevice device_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  VkDeviceSize allocated_ = 0;
  std::byte* mapped_ = nullptr;
  VkMemoryPropertyFlags memory_flags_ = 0;
};

// What Buffer::download makes on every call that stages (a kHostReadback buffer, a command buffer
// and a fence), made once, for a caller that reads back every frame: VulkanRuntime's copy calls on a
// GPU whose output buffers the host cannot read in place. One thread at a time.
class ReadbackStage {
 public:
  // Room for reads of up to `capacity` bytes (> 0).
  static Result<ReadbackStage> create(const Device& device, VkDeviceSize capacity);

  // As buffer.download(device, out, offset), reusing this stage's objects: nothing is allocated.
  // kInvalidArgument for a range past the buffer or more than capacity() bytes.
  Status download(const Device& device, const Buffer& buffer, std::span<std::byte> out, VkDeviceSize offset);
  VkDeviceSize capacity() const { return staging_.size(); }
  const Buffer& staging() const { return staging_; }  // for memory reports

 private:
  Buffer staging_;
  UniqueCommandPool pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;  // freed with the pool
  UniqueFence fence_;
};

// Memory of a set of buffers, for reports (RuntimeMemory): their allocations' bytes, and how many
// of them are device-local.
struct BufferTally {
  std::uint64_t bytes = 0;
  std::uint64_t device_local = 0;
  void add(const Buffer& buffer) {
    bytes += buffer.allocatedBytes();
    if ((buffer.memoryFlags() & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) != 0) device_local += buffer.allocatedBytes();
  }
};

// A shader input buffer (storage or uniform texel) holding `bytes`, at least 16 bytes long so
// empty arrays still give a valid descriptor. kUnavailable when it exceeds maxStorageBufferRange (one binding's limit).
Result<Buffer> createStorageBuffer(const Device& device, std::span<const std::byte> bytes,
                                   VkBufferUsageFlags extra_usage = 0, MemoryUse use = MemoryUse::kDeviceLocal);

// Typed helpers: upload/download a span of trivially copyable elements.
template <typename T>
Status uploadSpan(const Device& device, Buffer& buffer, std::span<const T> data, VkDeviceSize offset = 0) {
  return buffer.upload(device, std::as_bytes(data), offset);
}
template <typename T>
Status downloadSpan(const Device& device, const Buffer& buffer, std::span<T> out, VkDeviceSize offset = 0) {
  return buffer.download(device, std::as_writable_bytes(out), offset);
}

}  // namespace odeskin::vk
