// SPDX-License-Identifier: MIT
#include <cstdlib>
#include <sstream>
#include <string>

#include "gpu_test_support.hpp"
#include "host/buffer.hpp"
#include "host/device_info.hpp"
#include "host/shader_inputs.hpp"
#include "host/texel_bindings.hpp"
#include "host/vk_status.hpp"

namespace odeskin {
namespace {

using testing::GpuTest;

TEST(VkStatusTest, MapsResultsToCodes) {
  EXPECT_TRUE(vk::vkStatus(VK_SUCCESS, "x").ok());
  EXPECT_TRUE(vk::vkStatus(VK_INCOMPLETE, "x").ok());
  Status lost = vk::vkStatus(VK_ERROR_DEVICE_LOST, "vkQueueSubmit");
  EXPECT_EQ(lost.code(), StatusCode::kDeviceError);
  EXPECT_NE(lost.message().find("vkQueueSubmit"), std::string::npos);
  EXPECT_NE(lost.message().find("VK_ERROR_DEVICE_LOST"), std::string::npos);
  EXPECT_EQ(vk::vkStatus(VK_ERROR_OUT_OF_DEVICE_MEMORY, "x").code(), StatusCode::kDeviceError);
  EXPECT_EQ(vk::vkStatus(VK_ERROR_INITIALIZATION_FAILED, "x").code(), StatusCode::kUnavailable);
  EXPECT_EQ(vk::vkStatus(VK_ERROR_INCOMPATIBLE_DRIVER, "x").code(), StatusCode::kUnavailable);
}

TEST_F(GpuTest, ValidationIsOnWhenInstalled) {
  EXPECT_EQ(instance().validationEnabled(), vk::Instance::validationLayerInstalled());
}

// The fixture's zero-message check is only meaningful if the layer really reports: provoke one
// error (a wrong sType, harmless to the driver) and see it counted.
TEST_F(GpuTest, ValidationLayerReportsErrors) {
  if (!instance().validationEnabled()) GTEST_SKIP() << "validation layer not installed";
  VkFenceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;  // deliberately wrong
  VkFence fence = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateFence(device().handle(), &info, nullptr, &fence), VK_SUCCESS);
  vkDestroyFence(device().handle(), fence, nullptr);
  EXPECT_GT(log_.count(), 0u);
  log_.clear();
}

// Synchronization validation is what sees a missing barrier, and the layer leaves it off unless
// asked: two copies through one buffer with no barrier between them must be reported.
TEST_F(GpuTest, SynchronizationValidationReportsAMissingBarrier) {
  if (!instance().validationEnabled()) GTEST_SKIP() << "validation layer not installed";
  ASSERT_TRUE(instance().syncValidationEnabled());
  Result<vk::Buffer> a = vk::Buffer::create(device(), 256, vk::kOutputBufferUsage);
  Result<vk::Buffer> b = vk::Buffer::create(device(), 256, vk::kOutputBufferUsage);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_TRUE(device()
                  .submitAndWait([&](VkCommandBuffer cmd) {
                    const VkBufferCopy region{0, 0, 256};
                    vkCmdCopyBuffer(cmd, a->handle(), b->handle(), 1, &region);
                    vkCmdCopyBuffer(cmd, b->handle(), a->handle(), 1, &region);  // reads b before the write lands
                  })
                  .ok());
  bool hazard = false;
  for (const std::string& m : log_.messages()) hazard |= m.find("SYNC-HAZARD-READ-AFTER-WRITE") != std::string::npos;
  EXPECT_TRUE(hazard) << log_.count() << " messages";
  log_.clear();
}

TEST_F(GpuTest, AutoPicksADevice) {
  Result<std::uint32_t> index = vk::selectPhysicalDevice(instance(), "auto");
  ASSERT_TRUE(index.ok()) << index.status().toString();
  EXPECT_EQ(device().index(), *index);
  EXPECT_GT(std::string(device().name()).size(), 0u);
  EXPECT_NE(device().queueFlags() & VK_QUEUE_COMPUTE_BIT, 0u);
}

TEST_F(GpuTest, SelectsByIndexAndName) {
  Result<std::uint32_t> first = vk::selectPhysicalDevice(instance(), "0");
  ASSERT_TRUE(first.ok()) << first.status().toString();
  EXPECT_EQ(*first, 0u);
  Result<std::vector<VkPhysicalDevice>> devices = vk::physicalDevices(instance());
  ASSERT_TRUE(devices.ok());
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties((*devices)[0], &p);
  // A lower-cased piece of the first name must find it (or an earlier device with the same piece).
  std::string piece = std::string(p.deviceName).substr(0, 6);
  for (char& c : piece) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  Result<std::uint32_t> by_name = vk::selectPhysicalDevice(instance(), piece);
  ASSERT_TRUE(by_name.ok()) << by_name.status().toString();
  EXPECT_EQ(*by_name, 0u);
  if (std::string(p.deviceName).find("llvmpipe") != std::string::npos) {
    Result<std::uint32_t> llvmpipe = vk::selectPhysicalDevice(instance(), "LLVMpipe");
    ASSERT_TRUE(llvmpipe.ok());
    EXPECT_EQ(*llvmpipe, 0u);
  }
  Result<vk::Device> opened = vk::Device::create(instance(), "0");
  ASSERT_TRUE(opened.ok()) << opened.status().toString();
  EXPECT_STREQ(opened->name(), p.deviceName);
}

TEST_F(GpuTest, BadSelectorsListDevices) {
  for (const char* selector : {"99", "no-such-device-xyz"}) {
    Result<std::uint32_t> index = vk::selectPhysicalDevice(instance(), selector);
    ASSERT_FALSE(index.ok()) << selector;
    EXPECT_EQ(index.status().code(), StatusCode::kUnavailable);
    EXPECT_EQ(index.status().message().rfind(std::string("--device ") + selector + ": ", 0), 0u)
        << index.status().message();
    EXPECT_NE(index.status().message().find(device().name()), std::string::npos) << index.status().message();
    Result<vk::Device> opened = vk::Device::create(instance(), selector);
    EXPECT_EQ(opened.status().code(), StatusCode::kUnavailable);
  }
}

// A selector from the environment is named as such, so the user knows what to change; the device
// list stays on the error's one line. The environment changes while no other thread of the test
// reads it, hence the NOLINTs.
TEST_F(GpuTest, SelectorErrorsNameTheirSourceOnOneLine) {
  ASSERT_EQ(::setenv("ODESKIN_DEVICE", "99", 1), 0);  // NOLINT(concurrency-mt-unsafe)
  Result<std::uint32_t> index = vk::selectPhysicalDevice(instance(), "auto");
  ::unsetenv("ODESKIN_DEVICE");  // NOLINT(concurrency-mt-unsafe)
  ASSERT_FALSE(index.ok());
  EXPECT_EQ(index.status().code(), StatusCode::kUnavailable);
  EXPECT_EQ(index.status().message().rfind("ODESKIN_DEVICE=99: no device with that index; available devices: 0: ", 0),
            0u)
      << index.status().message();
  // The program prints a status as its one error line.
  EXPECT_EQ(index.status().message().find('\n'), std::string::npos) << index.status().message();
  Result<std::uint32_t> named = vk::selectPhysicalDevice(instance(), "no-such-device");
  ASSERT_FALSE(named.ok());
  EXPECT_EQ(named.status().message().find('\n'), std::string::npos) << named.status().message();
}

TEST_F(GpuTest, PrintDeviceInfoNamesTheDevice) {
  std::ostringstream out;
  Status status = vk::printDeviceInfo(out, "auto");
  ASSERT_TRUE(status.ok()) << status.toString();
  const std::string text = out.str();
  EXPECT_NE(text.find(device().name()), std::string::npos) << text;
  EXPECT_NE(text.find("maxStorageBufferRange"), std::string::npos);
  EXPECT_NE(text.find("timestampPeriod"), std::string::npos);
  EXPECT_NE(text.find("<- selected"), std::string::npos);
  // Vulkan requires a host-visible coherent memory type: staging buffers and per-frame inputs live there.
  EXPECT_NE(text.find("memory types: "), std::string::npos) << text;
  EXPECT_NE(text.find("host-visible+coherent"), std::string::npos) << text;

  std::ostringstream bad;
  EXPECT_EQ(vk::printDeviceInfo(bad, "no-such-device-xyz").code(), StatusCode::kUnavailable);
  EXPECT_NE(bad.str().find(device().name()), std::string::npos);
}

// Texel buffers unless the environment asks for storage buffers (the storage_inputs ctest entries
// run the parity tests that way on lavapipe); a value it does not know is refused by name rather
// than ignored. The environment changes while no other thread of the test reads it (the NOLINTs).
TEST(ShaderInputs, TexelBuffersUnlessTheEnvironmentSaysOtherwise) {
  const char* saved = std::getenv("ODESKIN_SHADER_INPUTS");
  const std::string restore = saved != nullptr ? saved : "";
  ::unsetenv("ODESKIN_SHADER_INPUTS");  // NOLINT(concurrency-mt-unsafe)
  Result<vk::ShaderInputs> inputs = vk::deformShaderInputs();
  ASSERT_TRUE(inputs.ok()) << inputs.status().toString();
  EXPECT_EQ(*inputs, vk::ShaderInputs::kTexel);
  EXPECT_EQ(vk::deformTexelTable(vk::ShaderInputs::kTexel).size(), std::size(vk::kDeformTexelBindings));
  EXPECT_TRUE(vk::deformTexelTable(vk::ShaderInputs::kStorage).empty());

  ::setenv("ODESKIN_SHADER_INPUTS", "storage", 1);  // NOLINT(concurrency-mt-unsafe)
  EXPECT_EQ(*vk::deformShaderInputs(), vk::ShaderInputs::kStorage);
  ::setenv("ODESKIN_SHADER_INPUTS", "texel", 1);  // NOLINT(concurrency-mt-unsafe)
  EXPECT_EQ(*vk::deformShaderInputs(), vk::ShaderInputs::kTexel);
  ::setenv("ODESKIN_SHADER_INPUTS", "ssbo", 1);  // NOLINT(concurrency-mt-unsafe)
  Result<vk::ShaderInputs> bad = vk::deformShaderInputs();
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(bad.status().message(), "ODESKIN_SHADER_INPUTS=ssbo: expected texel or storage");
  if (saved != nullptr) {
    ::setenv("ODESKIN_SHADER_INPUTS", restore.c_str(), 1);  // NOLINT(concurrency-mt-unsafe)
  } else {
    ::unsetenv("ODESKIN_SHADER_INPUTS");  // NOLINT(concurrency-mt-unsafe)
  }
}

}  // namespace
}  // namespace odeskin
