// SPDX-License-Identifier: MIT
#include "timestamp_queries.hpp"

#include "vk_status.hpp"

namespace odeskin::vk {

Result<TimestampQueries> TimestampQueries::create(const Device& device, std::uint32_t pairs) {
  TimestampQueries queries;
  queries.device_ = device.handle();
  std::uint32_t bits = device.timestampValidBits();
  if (bits == 0 || pairs == 0) return queries;
  // Only the low timestampValidBits bits are meaningful; mask before subtracting.
  queries.mask_ = bits >= 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << bits) - 1);
  queries.period_ns_ = static_cast<double>(device.limits().timestampPeriod);

  VkQueryPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2 * pairs;
  VkQueryPool pool = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateQueryPool(device.handle(), &info, nullptr, &pool));
  queries.pool_ = UniqueQueryPool(device.handle(), pool);
  return queries;
}

void TimestampQueries::recordBegin(VkCommandBuffer cmd, std::uint32_t pair) const {
  if (!pool_) return;
  // Queries must be reset before each write; doing it in the same command buffer keeps it in order.
  vkCmdResetQueryPool(cmd, pool_.get(), 2 * pair, 2);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_.get(), 2 * pair);
}

void TimestampQueries::recordEnd(VkCommandBuffer cmd, std::uint32_t pair) const {
  if (!pool_) return;
  // BOTTOM_OF_PIPE: written once everything recorded before it has finished.
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 2 * pair + 1);
}

Result<double> TimestampQueries::seconds(std::uint32_t pair) const {
  if (!pool_) return 0.0;
  std::uint64_t ticks[2] = {0, 0};
  // WAIT: the caller has waited on the fence (returns at once), or, for a frame an engine submitted,
  // seen its completion word, which the frame writes just before its end timestamp (may block briefly).
  ODESKIN_VK_TRY(vkGetQueryPoolResults(device_, pool_.get(), 2 * pair, 2, sizeof(ticks), ticks,
                                       sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  std::uint64_t delta = ((ticks[1] & mask_) - (ticks[0] & mask_)) & mask_;
  return static_cast<double>(delta) * period_ns_ * 1e-9;
}

}  // namespace odeskin::vk
