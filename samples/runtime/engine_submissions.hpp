// SPDX-License-Identifier: MIT
// The sample's stand-in for an engine's renderer when it runs with --record: its own command
// buffers and fences, one of each per frame in flight. Each frame's command buffer gets the
// runtime's commands (VulkanRuntime::recordFrame), then the barrier to vertex input where the
// engine's draws would follow, and the engine submits it. docs/runtime.md quotes record().
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.hpp"
#include "host/device.hpp"
#include "host/runtime/vulkan_runtime.hpp"
#include "host/vk_handle.hpp"

namespace odeskin {

class EngineSubmissions {
 public:
  // One command buffer and fence per frame in flight of `runtime`, on `device`; both must outlive this.
  static Result<EngineSubmissions> create(const vk::Device& device, VulkanRuntime& runtime);

  EngineSubmissions(EngineSubmissions&&) noexcept = default;
  EngineSubmissions& operator=(EngineSubmissions&&) = delete;
  EngineSubmissions(const EngineSubmissions&) = delete;
  EngineSubmissions& operator=(const EngineSubmissions&) = delete;
  // Waits for the submissions in flight: their command buffers must not die under the GPU.
  ~EngineSubmissions();

  // One frame: waits for the oldest submission, tells the runtime its frame is done, records the
  // next frame into that command buffer and submits it. Returns the frame's number.
  Result<std::uint64_t> record();
  // Waits for the submission holding `frame` and tells the runtime so (before reading the frame).
  Status complete(std::uint64_t frame);

 private:
  struct Slot {
    vk::UniqueCommandBuffer cmd;
    vk::UniqueFence fence;
    std::uint64_t frame = 0;  // the runtime's frame in the last submission, 0 before any
    bool pending = false;     // submitted and not waited for
  };
  EngineSubmissions(const vk::Device& device, VulkanRuntime& runtime) : device_(&device), runtime_(&runtime) {}
  Status waitFor(Slot& slot) const;

  const vk::Device* device_;
  VulkanRuntime* runtime_;
  vk::UniqueCommandPool pool_;  // before slots_, so their command buffers go first
  std::vector<Slot> slots_;
  std::uint32_t next_ = 0;
};

}  // namespace odeskin
