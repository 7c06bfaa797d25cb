// SPDX-License-Identifier: MIT
// GPU time of recorded work from a pair of timestamp queries (ticks x timestampPeriod ns). Wall
// time is the caller's business; this measures only what the device spends between the two marks.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "device.hpp"
#include "engine/core/result.hpp"
#include "vk_handle.hpp"

namespace odeskin::vk {

class TimestampQueries {
 public:
  // `pairs` independent begin/end pairs (one per frame in flight). On a queue without timestamp
  // support (timestampValidBits = 0) it creates nothing and supported() is false.
  static Result<TimestampQueries> create(const Device& device, std::uint32_t pairs);

  TimestampQueries() = default;
  TimestampQueries(TimestampQueries&&) noexcept = default;
  TimestampQueries& operator=(TimestampQueries&&) noexcept = default;

  bool supported() const { return static_cast<bool>(pool_); }
  // Resets pair `pair` and writes its begin mark; no-op when unsupported.
  void recordBegin(VkCommandBuffer cmd, std::uint32_t pair) const;
  // Writes the end mark once all earlier commands have completed.
  void recordEnd(VkCommandBuffer cmd, std::uint32_t pair) const;
  // Seconds between the marks of `pair`, whose submission has completed; 0 when unsupported.
  Result<double> seconds(std::uint32_t pair) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  UniqueQueryPool pool_;
  double period_ns_ = 1.0;
  std::uint64_t mask_ = ~std::uint64_t{0};
};

}  // namespace odeskin::vk
