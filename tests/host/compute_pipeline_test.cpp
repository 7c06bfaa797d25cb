// SPDX-License-Identifier: MIT
// ComputePipeline's texel bindings: the layout they build, the views bindBuffer makes (and replaces)
// and the limits it checks, under the validation layer (GpuTest fails on any message).
#include <cstdint>
#include <vector>

#include "gpu_test_support.hpp"
#include "host/buffer.hpp"
#include "host/compute_pipeline.hpp"
#include "host/texel_bindings.hpp"
#include "shaders/lbs.spv.h"

namespace odeskin {
namespace {

using testing::GpuTest;

// lbs.comp's bindings: the output as a storage buffer, its inputs as texel buffers.
constexpr std::uint32_t kLbsBindings[] = {ODESKIN_BINDING_REST_POSITIONS, ODESKIN_BINDING_INFLUENCE_OFFSETS,
                                          ODESKIN_BINDING_INFLUENCES,     ODESKIN_BINDING_BONES,
                                          ODESKIN_BINDING_BONE_DUAL_QUATS, ODESKIN_BINDING_OUT_POSITIONS};

TEST_F(GpuTest, ComputePipelineSortsTexelAndStorageBindings) {
  const vk::SortedBindings sorted = vk::SortedBindings::sort(kLbsBindings, vk::kDeformTexelBindings);
  EXPECT_EQ(sorted.storage, std::vector<std::uint32_t>{ODESKIN_BINDING_OUT_POSITIONS});
  ASSERT_EQ(sorted.texels.size(), 5u);
  EXPECT_EQ(sorted.texels[0].format, VK_FORMAT_R32G32B32A32_SFLOAT);  // rest positions
  EXPECT_EQ(sorted.texels[2].format, VK_FORMAT_R32G32_UINT);          // influences

  vk::ComputePipelineDesc desc;
  desc.spirv = kLbsSpirv;
  desc.storage_bindings = sorted.storage;
  desc.texel_bindings = sorted.texels;
  desc.push_constant_bytes = sizeof(gpu::DeformPushConstants);
  desc.descriptor_set_count = 2;
  Result<vk::ComputePipeline> pipeline = vk::ComputePipeline::create(device(), desc);
  ASSERT_TRUE(pipeline.ok()) << pipeline.status().toString();

  // Bind every input twice in both sets: the second view replaces the first without a validation
  // message, at an offset of one texel and a range of two.
  Result<vk::Buffer> buffer = vk::Buffer::create(device(), 256, vk::kOutputBufferUsage);
  ASSERT_TRUE(buffer.ok());
  for (std::uint32_t set = 0; set < 2; ++set) {
    for (const vk::TexelBinding& t : sorted.texels) {
      EXPECT_TRUE(pipeline->bindBuffer(set, t.binding, buffer->handle()).ok());
      EXPECT_TRUE(pipeline->bindBuffer(set, t.binding, buffer->handle(), 16, 32).ok());
    }
    EXPECT_TRUE(pipeline->bindBuffer(set, ODESKIN_BINDING_OUT_POSITIONS, buffer->handle()).ok());
  }
}

TEST_F(GpuTest, ComputePipelineRejectsBadTexelBindings) {
  vk::ComputePipelineDesc desc;
  desc.spirv = kLbsSpirv;
  const std::uint32_t storage[] = {ODESKIN_BINDING_OUT_POSITIONS, ODESKIN_BINDING_BONES};
  const vk::TexelBinding both[] = {{ODESKIN_BINDING_BONES, VK_FORMAT_R32G32B32A32_SFLOAT}};
  desc.storage_bindings = storage;
  desc.texel_bindings = both;
  Result<vk::ComputePipeline> twice = vk::ComputePipeline::create(device(), desc);
  EXPECT_EQ(twice.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(twice.status().message().find("binding 9 is both"), std::string::npos) << twice.status().toString();

  const vk::TexelBinding rgb[] = {{ODESKIN_BINDING_BONES, VK_FORMAT_R32G32B32_SFLOAT}};
  desc.storage_bindings = {};
  desc.texel_bindings = rgb;
  Result<vk::ComputePipeline> format = vk::ComputePipeline::create(device(), desc);
  EXPECT_EQ(format.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(format.status().message().find("texel format"), std::string::npos) << format.status().toString();
}

TEST_F(GpuTest, ComputePipelineRefusesMoreTexelsThanTheDeviceAllows) {
  const vk::SortedBindings sorted = vk::SortedBindings::sort(kLbsBindings, vk::kDeformTexelBindings);
  vk::ComputePipelineDesc desc;
  desc.spirv = kLbsSpirv;
  desc.storage_bindings = sorted.storage;
  desc.texel_bindings = sorted.texels;
  desc.push_constant_bytes = sizeof(gpu::DeformPushConstants);
  Result<vk::ComputePipeline> pipeline = vk::ComputePipeline::create(device(), desc);
  ASSERT_TRUE(pipeline.ok()) << pipeline.status().toString();
  Result<vk::Buffer> buffer = vk::Buffer::create(device(), 64, vk::kOutputBufferUsage);
  ASSERT_TRUE(buffer.ok());
  // Checked before any view is made, so the buffer need not be that large.
  const VkDeviceSize too_many = (VkDeviceSize{device().limits().maxTexelBufferElements} + 1) * 16;
  const Status status = pipeline->bindBuffer(0, ODESKIN_BINDING_REST_POSITIONS, buffer->handle(), 0, too_many);
  EXPECT_EQ(status.code(), StatusCode::kUnavailable);
  EXPECT_NE(status.message().find("maxTexelBufferElements"), std::string::npos) << status.toString();
}

}  // namespace
}  // namespace odeskin
