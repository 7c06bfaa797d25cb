// SPDX-License-Identifier: MIT
#include "device_bandwidth.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <string>

#include "host/buffer.hpp"
#include "host/compute_pipeline.hpp"
#include "host/timestamp_queries.hpp"
#include "shaders/copy_probe.spv.h"

namespace odeskin::bench {
namespace {

constexpr std::uint32_t kProbeWorkgroup = 256;  // copy_probe.comp's local_size_x

Status checkArguments(VkDeviceSize bytes, int repeats) {
  if (bytes == 0 || repeats < 1) {
    return invalidArgument("bench: the copy bandwidth needs bytes > 0 and repeats >= 1 (got " + std::to_string(bytes) +
                           ", " + std::to_string(repeats) + ")");
  }
  return okStatus();
}

// The best of `repeats` submissions of `record` (one copy of `bytes`), as 2 x bytes per second.
Result<CopyBandwidth> bestCopy(const vk::Device& device, VkDeviceSize bytes, int repeats,
                               const std::function<void(VkCommandBuffer)>& record) {
  ODESKIN_ASSIGN_OR_RETURN(const vk::TimestampQueries timer, vk::TimestampQueries::create(device, 1));
  CopyBandwidth result;
  result.bytes = bytes;
  result.timestamps = timer.supported();
  double fastest = std::numeric_limits<double>::infinity();
  // The first copy also pays for first touches of the memory; the best of several is the rate.
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    ODESKIN_TRY(device.submitAndWait([&](VkCommandBuffer cmd) {
      timer.recordBegin(cmd, 0);
      record(cmd);
      timer.recordEnd(cmd, 0);
    }));
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (result.timestamps) {
      ODESKIN_ASSIGN_OR_RETURN(seconds, timer.seconds(0));
    }
    if (seconds > 0.0) fastest = std::min(fastest, seconds);
  }
  if (!(fastest < std::numeric_limits<double>::infinity())) {
    return internalError("bench: every " + std::to_string(bytes) + "-byte copy timed as 0 s");
  }
  result.bytes_per_second = 2.0 * static_cast<double>(bytes) / fastest;
  return result;
}

}  // namespace

Result<CopyBandwidth> deviceCopyBandwidth(const vk::Device& device, VkDeviceSize bytes, int repeats) {
  ODESKIN_TRY(checkArguments(bytes, repeats));
  ODESKIN_ASSIGN_OR_RETURN(const vk::Buffer source, vk::Buffer::create(device, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT));
  ODESKIN_ASSIGN_OR_RETURN(const vk::Buffer target, vk::Buffer::create(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT));
  return bestCopy(device, bytes, repeats, [&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, source.handle(), target.handle(), 1, &region);
  });
}

Result<CopyBandwidth> shaderCopyBandwidth(const vk::Device& device, VkDeviceSize bytes, int repeats) {
  ODESKIN_TRY(checkArguments(bytes, repeats));
  if (bytes % 16 != 0 || bytes > device.limits().maxStorageBufferRange || bytes / 16 > UINT32_MAX) {
    return invalidArgument("bench: the shader copy needs a multiple of 16 bytes within maxStorageBufferRange (got " +
                           std::to_string(bytes) + ")");
  }
  ODESKIN_ASSIGN_OR_RETURN(const vk::Buffer source, vk::Buffer::create(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
  ODESKIN_ASSIGN_OR_RETURN(const vk::Buffer target, vk::Buffer::create(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
  const std::uint32_t bindings[] = {0, 1};
  vk::ComputePipelineDesc desc;
  desc.spirv = kCopyProbeSpirv;
  desc.storage_bindings = bindings;
  desc.push_constant_bytes = 2 * sizeof(std::uint32_t);
  ODESKIN_ASSIGN_OR_RETURN(vk::ComputePipeline pipeline, vk::ComputePipeline::create(device, desc));
  ODESKIN_TRY(pipeline.bindBuffer(0, 0, source.handle()));
  ODESKIN_TRY(pipeline.bindBuffer(0, 1, target.handle()));
  const auto count = static_cast<std::uint32_t>(bytes / 16);
  // Enough workgroups to fill any GPU, within the x limit Vulkan guarantees every device (65,535).
  const std::uint32_t groups = std::min<std::uint32_t>((count + kProbeWorkgroup - 1) / kProbeWorkgroup, 65'535);
  const std::uint32_t push[2] = {count, groups * kProbeWorkgroup};
  return bestCopy(device, bytes, repeats, [&](VkCommandBuffer cmd) { pipeline.recordDispatch(cmd, 0, push, groups); });
}

}  // namespace odeskin::bench
