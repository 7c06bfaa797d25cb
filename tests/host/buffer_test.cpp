// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cstdint>
#include <string>
#include <numeric>
#include <vector>

#include "gpu_test_support.hpp"
#include "host/buffer.hpp"

namespace odeskin {
namespace {

using testing::GpuTest;

TEST_F(GpuTest, BufferRoundTripMappedAndStaged) {
  std::vector<std::uint32_t> data(1000);
  std::iota(data.begin(), data.end(), 7u);
  for (vk::MemoryUse use : {vk::MemoryUse::kDeviceLocal, vk::MemoryUse::kDeviceLocalStaged,
                            vk::MemoryUse::kHostVisible, vk::MemoryUse::kHostReadback}) {
    Result<vk::Buffer> buffer = vk::Buffer::create(device(), data.size() * 4, vk::kOutputBufferUsage, use);
    ASSERT_TRUE(buffer.ok()) << buffer.status().toString();
    if (use == vk::MemoryUse::kDeviceLocalStaged) {
      EXPECT_EQ(buffer->mapped(), nullptr);
    }
    if (use == vk::MemoryUse::kHostVisible || use == vk::MemoryUse::kHostReadback) {
      EXPECT_NE(buffer->mapped(), nullptr);
    }
    ASSERT_TRUE(vk::uploadSpan<std::uint32_t>(device(), *buffer, data).ok());
    std::vector<std::uint32_t> back(data.size(), 0);
    ASSERT_TRUE(vk::downloadSpan<std::uint32_t>(device(), *buffer, back).ok());
    EXPECT_EQ(back, data);
    // A partial write at an offset leaves the rest alone.
    std::vector<std::uint32_t> patch = {1, 2, 3};
    ASSERT_TRUE(vk::uploadSpan<std::uint32_t>(device(), *buffer, patch, 40).ok());
    ASSERT_TRUE(vk::downloadSpan<std::uint32_t>(device(), *buffer, std::span(back)).ok());
    EXPECT_EQ(back[10], 1u);
    EXPECT_EQ(back[12], 3u);
    EXPECT_EQ(back[13], data[13]);
  }
}

// The runtime's copy calls on a discrete GPU: one stage, many reads, nothing allocated per read
// (Buffer::download makes a staging buffer, a command pool and a fence every time).
TEST_F(GpuTest, ReadbackStageReadsStagedBuffersAgainAndAgain) {
  std::vector<std::uint32_t> data(1000);
  std::iota(data.begin(), data.end(), 11u);
  Result<vk::Buffer> staged = vk::Buffer::create(device(), data.size() * 4, vk::kOutputBufferUsage,
                                                 vk::MemoryUse::kDeviceLocalStaged);
  ASSERT_TRUE(staged.ok()) << staged.status().toString();
  ASSERT_EQ(staged->mapped(), nullptr);
  ASSERT_TRUE(vk::uploadSpan<std::uint32_t>(device(), *staged, data).ok());
  Result<vk::ReadbackStage> stage = vk::ReadbackStage::create(device(), 400);
  ASSERT_TRUE(stage.ok()) << stage.status().toString();
  EXPECT_EQ(stage->capacity(), 400u);
  std::vector<std::uint32_t> back(100);
  for (std::uint32_t round = 0; round < 3; ++round) {
    for (std::uint32_t part = 0; part < 10; ++part) {
      std::fill(back.begin(), back.end(), 0u);
      ASSERT_TRUE(stage->download(device(), *staged, std::as_writable_bytes(std::span(back)), part * 400).ok());
      EXPECT_TRUE(std::equal(back.begin(), back.end(), data.begin() + part * 100)) << round << " " << part;
    }
  }
  std::vector<std::uint32_t> too_many(101);
  const Status over = stage->download(device(), *staged, std::as_writable_bytes(std::span(too_many)), 0);
  EXPECT_EQ(over.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(over.message().find("exceed its capacity of 400"), std::string::npos) << over.message();
  EXPECT_EQ(stage->download(device(), *staged, std::as_writable_bytes(std::span(back)), 3700).code(),
            StatusCode::kInvalidArgument);  // past the buffer's end
  // A mapped, cached buffer is read in place, whatever its size.
  Result<vk::Buffer> mapped = vk::Buffer::create(device(), data.size() * 4, vk::kOutputBufferUsage, vk::MemoryUse::kHostReadback);
  ASSERT_TRUE(mapped.ok());
  ASSERT_TRUE(vk::uploadSpan<std::uint32_t>(device(), *mapped, data).ok());
  if (vk::hostReadsDirectly(mapped->memoryFlags())) {
    std::vector<std::uint32_t> all(data.size());
    ASSERT_TRUE(stage->download(device(), *mapped, std::as_writable_bytes(std::span(all)), 0).ok());
    EXPECT_EQ(all, data);
  }
}

// Only cached mappings are read in place: a discrete GPU's mappable device memory (ReBAR) and
// write-combined host memory are slow for the CPU to read, so downloads stage those.
TEST(BufferMemory, OnlyCachedMappingsAreReadDirectly) {
  constexpr VkMemoryPropertyFlags kVisible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  EXPECT_TRUE(vk::hostReadsDirectly(kVisible | VK_MEMORY_PROPERTY_HOST_CACHED_BIT));  // host memory, cached
  EXPECT_TRUE(vk::hostReadsDirectly(kVisible | VK_MEMORY_PROPERTY_HOST_CACHED_BIT |
                                    VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT));          // lavapipe, integrated GPUs
  EXPECT_FALSE(vk::hostReadsDirectly(kVisible | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT));  // ReBAR
  EXPECT_FALSE(vk::hostReadsDirectly(kVisible));                                       // write-combined host memory
}

// A readback buffer is the host's to read: cached wherever the device offers cached memory.
TEST_F(GpuTest, ReadbackBuffersPreferCachedMemory) {
  Result<vk::Buffer> buffer = vk::Buffer::create(device(), 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::kHostReadback);
  ASSERT_TRUE(buffer.ok()) << buffer.status().toString();
  bool device_has_cached = false;
  const VkPhysicalDeviceMemoryProperties& memory = device().memoryProperties();
  for (std::uint32_t t = 0; t < memory.memoryTypeCount; ++t) {
    device_has_cached |= (memory.memoryTypes[t].propertyFlags & VK_MEMORY_PROPERTY_HOST_CACHED_BIT) != 0;
  }
  EXPECT_EQ((buffer->memoryFlags() & VK_MEMORY_PROPERTY_HOST_CACHED_BIT) != 0, device_has_cached);
}

TEST_F(GpuTest, BufferRejectsOutOfRangeAndEmpty) {
  EXPECT_EQ(vk::Buffer::create(device(), 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT).status().code(),
            StatusCode::kInvalidArgument);
  Result<vk::Buffer> buffer = vk::Buffer::create(device(), 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ASSERT_TRUE(buffer.ok());
  std::vector<std::uint32_t> big(5, 0);
  EXPECT_EQ(vk::uploadSpan<std::uint32_t>(device(), *buffer, big).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(vk::downloadSpan<std::uint32_t>(device(), *buffer, std::span(big)).code(), StatusCode::kInvalidArgument);
  // Empty arrays still give a bindable 16-byte storage buffer.
  Result<vk::Buffer> empty = vk::createStorageBuffer(device(), {});
  ASSERT_TRUE(empty.ok());
  EXPECT_EQ(empty->size(), 16u);
}

TEST_F(GpuTest, BufferMovesOwnership) {
  Result<vk::Buffer> created = vk::Buffer::create(device(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ASSERT_TRUE(created.ok());
  VkBuffer handle = created->handle();
  vk::Buffer moved = std::move(created).value();
  EXPECT_EQ(moved.handle(), handle);
  vk::Buffer assigned;
  assigned = std::move(moved);
  EXPECT_EQ(assigned.handle(), handle);
  EXPECT_EQ(moved.handle(), VK_NULL_HANDLE);  // NOLINT: checking the moved-from state on purpose
}

}  // namespace
}  // namespace odeskin
