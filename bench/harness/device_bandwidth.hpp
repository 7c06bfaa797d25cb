// SPDX-License-Identifier: MIT
// What the device's memory sustains, measured rather than read from a data sheet (Vulkan reports no
// bandwidth): vkCmdCopyBuffer between two device-local buffers, timed by timestamp queries (by the
// submission's wall time where the queue has none), the best of a few copies, counted as 2 x bytes
// per copy since every byte is read once and written once. The Vulkan records' bytes per second are
// set against it. On lavapipe it is a memcpy on the host.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "engine/core/result.hpp"
#include "host/device.hpp"

namespace odeskin::bench {

struct CopyBandwidth {
  VkDeviceSize bytes = 0;           // of each buffer
  double bytes_per_second = 0.0;    // 2 x bytes / the fastest copy
  bool timestamps = false;          // timed by timestamp queries (else wall time)
};

// kInvalidArgument for bytes = 0 or repeats < 1; the buffer and driver errors otherwise (out of
// device memory: kUnavailable or kDeviceError, naming the size).
Result<CopyBandwidth> deviceCopyBandwidth(const vk::Device& device, VkDeviceSize bytes, int repeats = 5);

}  // namespace odeskin::bench
