// SPDX-License-Identifier: MIT
// What the device's memory sustains, measured rather than read from a data sheet (Vulkan reports no
// bandwidth), two ways between two device-local buffers: vkCmdCopyBuffer (on lavapipe a memcpy on
// the host; on a GPU perhaps a copy engine), and shaders/copy_probe.comp (a GPU's load and store
// units, as the deformation shaders use them). Each is timed by timestamp queries (by the
// submission's wall time where the queue has none), the best of a few copies, counted as 2 x bytes
// per copy since every byte is read once and written once. The Vulkan records' bytes per second are
// set against the faster of the two.
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
// The same through copy_probe.comp (`bytes` a multiple of 16; kInvalidArgument otherwise, or when
// the buffers exceed maxStorageBufferRange).
Result<CopyBandwidth> shaderCopyBandwidth(const vk::Device& device, VkDeviceSize bytes, int repeats = 5);

}  // namespace odeskin::bench
