// SPDX-License-Identifier: MIT
#include "device_bandwidth.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include "host/buffer.hpp"
#include "host/timestamp_queries.hpp"

namespace odeskin::bench {

Result<CopyBandwidth> deviceCopyBandwidth(const vk::Device& device, VkDeviceSize bytes, int repeats) {
  if (bytes == 0 || repeats < 1) {
    return invalidArgument("bench: the copy bandwidth needs bytes > 0 and repeats >= 1 (got " + std::to_string(bytes) +
                           ", " + std::to_string(repeats) + ")");
  }
  ODESKIN_ASSIGN_OR_RETURN(const vk::Buffer source, vk::Buffer::create(device, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT));
  ODESKIN_ASSIGN_OR_RETURN(const vk::Buffer target, vk::Buffer::create(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT));
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
      const VkBufferCopy region{0, 0, bytes};
      vkCmdCopyBuffer(cmd, source.handle(), target.handle(), 1, &region);
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

}  // namespace odeskin::bench
