// SPDX-License-Identifier: MIT
#include "vulkan_runtime.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <iterator>
#include <string>

#include "host/compute_dispatcher.hpp"
#include "host/shader_inputs.hpp"
#include "host/texel_bindings.hpp"
#include "shaders/fold_series.spv.h"
#include "shaders/instance_normals.spv.h"
#include "shaders/instance_tangents.spv.h"
#include "shaders/instanced_deform.spv.h"
#include "shaders/instanced_deform_shared.spv.h"
#include "shaders/instanced_deform_shared_storage.spv.h"
#include "shaders/instanced_deform_storage.spv.h"
#include "shaders/render_gather.spv.h"

namespace odeskin {
namespace {

template <typename T>
std::span<const std::byte> bytesOf(std::span<const T> v) {
  return std::as_bytes(v);
}

Status tooLarge(const char* what, VkDeviceSize bytes, const vk::Device& device) {
  return unavailable("vulkan runtime: " + std::string(what) + " take " + std::to_string(bytes) +
                     " bytes, more than maxStorageBufferRange (" +
                     std::to_string(device.limits().maxStorageBufferRange) + " bytes) of " + device.name() +
                     "; lower the capacity or split the instances over several runtimes");
}

// Every preset's rates back to back, in preset order (RuntimeAsset::ratesOffset's order).
std::vector<gpu::Float4> allRates(const RuntimeAsset& asset) {
  std::vector<gpu::Float4> rates;
  for (std::uint32_t p = 0; p < asset.presetCount(); ++p) {
    const auto& r = asset.packed(p).rates;
    rates.insert(rates.end(), r.begin(), r.end());
  }
  return rates;
}

// One frame's folded coefficients: every instance's copy of a segment's C x (2N + 2) entries.
VkDeviceSize foldedBytes(const RuntimeAsset& asset, std::uint32_t capacity) {
  const PackedDeformData& d = asset.packed(0);
  return VkDeviceSize{capacity} * d.curve_count * gpu::coefficientsPerCurve(d.modes) * sizeof(gpu::Float4);
}

// Whether compute shaders on `device` have subgroup arithmetic (instanced_deform.comp reduces the
// bounds with subgroupMin/Max; instanced_deform_shared.comp is the fallback).
bool subgroupArithmetic(const vk::Device& device) {
  if (device.properties().apiVersion < VK_API_VERSION_1_1) return false;
  VkPhysicalDeviceSubgroupProperties subgroup{};
  subgroup.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES;
  VkPhysicalDeviceProperties2 properties{};
  properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  properties.pNext = &subgroup;
  vkGetPhysicalDeviceProperties2(device.physicalDevice(), &properties);
  return (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) != 0 &&
         (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BASIC_BIT) != 0 &&
         (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT) != 0;
}

// One dispatch of `pipeline` with `push` over (x, y) workgroups, descriptor set `slot`.
void dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, std::uint32_t slot, const void* push,
              std::uint32_t push_bytes, std::uint32_t x, std::uint32_t y) {
  VkDescriptorSet set = pipeline.set(slot);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes, push);
  vkCmdDispatch(cmd, x, y, 1);
}

// kUnavailable when `count` `what` (one invocation each) need more workgroups than a dispatch's x extent.
Status checkGroupsX(const vk::Device& device, std::uint32_t count, const char* what) {
  const std::uint32_t groups = gpu::workgroupsFor(count);
  if (groups <= device.limits().maxComputeWorkGroupCount[0]) return okStatus();
  return unavailable("vulkan runtime: " + std::to_string(count) + " " + what + " need " + std::to_string(groups) +
                     " workgroups, more than maxComputeWorkGroupCount[0] of " + device.name());
}

// kUnavailable, naming the limit, when `options` cannot run on `device` in one dispatch.
Status checkDeviceLimits(const vk::Device& device, const RuntimeAsset& asset, const RuntimeOptions& options) {
  const VkPhysicalDeviceLimits& limits = device.limits();
  const std::uint32_t v = asset.vertexCount();
  if (options.capacity > limits.maxComputeWorkGroupCount[1]) {
    return unavailable("vulkan runtime: capacity " + std::to_string(options.capacity) +
                       " exceeds maxComputeWorkGroupCount[1] (" + std::to_string(limits.maxComputeWorkGroupCount[1]) +
                       ") of " + device.name());
  }
  ODESKIN_TRY(checkGroupsX(device, v, "vertices"));
  const VkDeviceSize out_bytes = VkDeviceSize{options.capacity} * v * sizeof(gpu::Float4);
  if (out_bytes > limits.maxStorageBufferRange) return tooLarge("one frame's positions", out_bytes, device);
  const VkDeviceSize fold_bytes = foldedBytes(asset, options.capacity);
  if (fold_bytes > limits.maxStorageBufferRange) return tooLarge("one frame's folded coefficients", fold_bytes, device);
  if (gathersRenderVertices(asset, options) || options.tangents) {
    const std::uint32_t r = asset.renderVertexCount();
    ODESKIN_TRY(checkGroupsX(device, r, "render vertices"));
    const VkDeviceSize render_bytes = VkDeviceSize{options.capacity} * r * sizeof(gpu::Float4);
    if (render_bytes > limits.maxStorageBufferRange) {
      return tooLarge(options.tangents ? "one frame's tangents" : "one frame's render-vertex positions", render_bytes,
                      device);
    }
  }
  return okStatus();
}

}  // namespace

Result<VulkanRuntime> VulkanRuntime::create(const vk::Device& device, const RuntimeAsset& asset,
                                            const RuntimeOptions& options, VulkanRuntimePaths paths) {
  ODESKIN_TRY(checkOptions(asset, options));
  ODESKIN_TRY(checkDeviceLimits(device, asset, options));
  VulkanRuntime rt(asset, options);
  rt.device_ = &device;
  rt.reuse_stages_ = vk::outputReuseStages(device);
  rt.groups_x_ = gpu::workgroupsFor(asset.vertexCount());
  rt.render_groups_x_ = gpu::workgroupsFor(asset.renderVertexCount());
  rt.subgroup_bounds_ = paths.allow_subgroups && subgroupArithmetic(device);
  rt.recorded_frames_.assign(options.frames_in_flight, 0);
  rt.records_.resize(options.capacity);
  rt.bones_.resize(std::size_t{options.capacity} * asset.boneCount());
  rt.basis_.resize(std::size_t{options.capacity} * asset.basisEntries());
  ODESKIN_TRY(rt.uploadAsset());

  // One frame's inputs in each ring slot: instance records, bones (and dual quaternions), basis.
  vk::FrameInputLayout layout(device);
  rt.records_offset_ = layout.add(ODESKIN_RT_BINDING_INSTANCES, rt.records_.size() * sizeof(gpu::InstanceRecord));
  rt.palettes_ = vk::BonePaletteWriter::plan(layout, ODESKIN_RT_BINDING_BONES, ODESKIN_RT_BINDING_BONE_DUAL_QUATS,
                                             rt.bones_.size(), asset.packed().skinning);
  rt.basis_offset_ = layout.add(ODESKIN_RT_BINDING_MODE_BASIS, rt.basis_.size() * sizeof(gpu::ModeBasis));
  ODESKIN_TRY(layout.checkLimits("vulkan runtime"));
  ODESKIN_ASSIGN_OR_RETURN(rt.ring_, vk::FrameRing::create(device, vk::FrameRingDesc{options.frames_in_flight,
                                                                                     layout.totalBytes()}));
  ODESKIN_TRY(rt.createSlots(paths.bounds));
  ODESKIN_TRY(rt.createPipelines(layout));
  return rt;
}

Status VulkanRuntime::uploadAsset() {
  // Device-local, read every frame (mapped on lavapipe/ReBAR, staged elsewhere). RATES holds every
  // preset's rates back to back (RuntimeAsset::ratesOffset).
  const RuntimeAsset& a = asset();
  const PackedDeformData& data = a.packed(0);
  const std::vector<gpu::Float4> rates = allRates(a);
  const std::pair<std::uint32_t, std::span<const std::byte>> arrays[] = {
      {ODESKIN_BINDING_REST_POSITIONS, bytesOf(std::span(data.rest_positions))},
      {ODESKIN_BINDING_VERTEX_BINDINGS, bytesOf(std::span(data.bindings))},
      {ODESKIN_BINDING_SEGMENT_VERTICES, bytesOf(std::span(data.segment_vertices))},
      {ODESKIN_BINDING_REMAINDERS, bytesOf(std::span(data.remainders))},
      {ODESKIN_BINDING_CURVE_MATERIALS, bytesOf(std::span(data.curve_materials))},
      {ODESKIN_BINDING_COEFFICIENTS, bytesOf(std::span(data.coefficients))},
      {ODESKIN_BINDING_RATES, bytesOf(std::span(rates))},
      {ODESKIN_BINDING_INFLUENCE_OFFSETS, bytesOf(std::span(data.influence_offsets))},
      {ODESKIN_BINDING_INFLUENCES, bytesOf(std::span(data.influences))},
  };
  for (const auto& [binding, bytes] : arrays) {
    ODESKIN_ASSIGN_OR_RETURN(vk::Buffer buffer, vk::createStorageBuffer(*device_, bytes));
    deform_statics_.emplace_back(binding, std::move(buffer));
  }
  ODESKIN_ASSIGN_OR_RETURN(corner_offsets_, vk::createStorageBuffer(*device_, bytesOf(a.cornerOffsets())));
  ODESKIN_ASSIGN_OR_RETURN(corners_, vk::createStorageBuffer(*device_, bytesOf(a.corners())));
  if (gathersRenderVertices()) {
    ODESKIN_ASSIGN_OR_RETURN(render_topology_, vk::createStorageBuffer(*device_, bytesOf(a.renderTopology())));
  }
  if (computesRenderNormals()) {
    ODESKIN_ASSIGN_OR_RETURN(render_corner_offsets_, vk::createStorageBuffer(*device_, bytesOf(a.renderCornerOffsets())));
    ODESKIN_ASSIGN_OR_RETURN(render_corners_, vk::createStorageBuffer(*device_, bytesOf(a.renderCorners())));
  }
  if (options().tangents) {
    ODESKIN_ASSIGN_OR_RETURN(tangent_frames_, vk::createStorageBuffer(*device_, bytesOf(a.tangentFrames())));
    ODESKIN_ASSIGN_OR_RETURN(tangent_weights_, vk::createStorageBuffer(*device_, bytesOf(a.tangentWeights())));
  }
  return okStatus();
}

Status VulkanRuntime::createSlots(BoundsReadback bounds) {
  // Each slot's outputs: positions and normals (storage + vertex + copy source), bounds readable.
  const VkDeviceSize out_bytes = VkDeviceSize{capacity()} * asset().vertexCount() * sizeof(gpu::Float4);
  const VkDeviceSize bytes = out_bytes < 16 ? 16 : out_bytes;
  const VkDeviceSize bounds_bytes = std::max<VkDeviceSize>(VkDeviceSize{capacity()} * sizeof(gpu::BoundsKeys), 32);
  const VkDeviceSize fold_bytes = std::max<VkDeviceSize>(foldedBytes(asset(), capacity()), 16);
  ODESKIN_ASSIGN_OR_RETURN(folded_, vk::Buffer::create(*device_, fold_bytes, vk::kShaderInputUsage));
  for (std::uint32_t s = 0; s < framesInFlight(); ++s) {
    Slot slot;
    ODESKIN_ASSIGN_OR_RETURN(slot.positions, vk::Buffer::create(*device_, bytes, vk::kOutputBufferUsage));
    if (options().normals && !computesRenderNormals()) {
      ODESKIN_ASSIGN_OR_RETURN(slot.normals, vk::Buffer::create(*device_, bytes, vk::kOutputBufferUsage));
    }
    ODESKIN_TRY(createBounds(slot, bounds_bytes, bounds));
    if (gathersRenderVertices()) {
      const VkDeviceSize render_bytes =
          std::max<VkDeviceSize>(VkDeviceSize{capacity()} * asset().renderVertexCount() * sizeof(gpu::Float4), 16);
      ODESKIN_ASSIGN_OR_RETURN(slot.render_positions, vk::Buffer::create(*device_, render_bytes, vk::kOutputBufferUsage));
      if (options().normals) {
        ODESKIN_ASSIGN_OR_RETURN(slot.render_normals, vk::Buffer::create(*device_, render_bytes, vk::kOutputBufferUsage));
      }
    }
    if (options().tangents) {
      const VkDeviceSize tangent_bytes =
          std::max<VkDeviceSize>(VkDeviceSize{capacity()} * outputVertexCount() * sizeof(gpu::Float4), 16);
      ODESKIN_ASSIGN_OR_RETURN(slot.tangents, vk::Buffer::create(*device_, tangent_bytes, vk::kOutputBufferUsage));
    }
    slots_.push_back(std::move(slot));
  }
  // Where the host cannot read the outputs in place (a discrete GPU), copy calls stage one
  // instance's output through buffers made now, not per call.
  if (!outPositions(0).readsInPlace()) {
    const VkDeviceSize instance_bytes = std::max<VkDeviceSize>(VkDeviceSize{outputVertexCount()} * sizeof(gpu::Float4), 16);
    ODESKIN_ASSIGN_OR_RETURN(readback_, vk::ReadbackStage::create(*device_, instance_bytes));
  }
  return okStatus();
}

RuntimeMemory VulkanRuntime::memory() const {
  vk::BufferTally asset;
  for (const auto& [binding, buffer] : deform_statics_) asset.add(buffer);
  for (const vk::Buffer* b : {&corner_offsets_, &corners_, &render_corner_offsets_, &render_corners_, &render_topology_,
                              &tangent_frames_, &tangent_weights_}) {
    asset.add(*b);
  }
  vk::BufferTally inputs;
  inputs.add(folded_);
  ring_.countBuffers(inputs);
  vk::BufferTally outputs;
  for (const Slot& slot : slots_) {
    for (const vk::Buffer* b : {&slot.positions, &slot.normals, &slot.bounds, &slot.bounds_readback, &slot.render_positions,
                                &slot.render_normals, &slot.tangents}) {
      outputs.add(*b);
    }
  }
  if (readback_) outputs.add(readback_->staging());
  RuntimeMemory m;
  m.capacity = capacity();
  m.asset = asset.bytes;
  // Host memory too: the instances' states, and the copy of a frame's inputs prepared before its slot is free.
  m.inputs = inputs.bytes + instanceStateBytes() + reservedBytes(records_) + reservedBytes(bones_) + reservedBytes(basis_);
  m.outputs = outputs.bytes;
  m.device_local = asset.device_local + inputs.device_local + outputs.device_local;
  return m;
}

Status VulkanRuntime::createBounds(Slot& slot, VkDeviceSize bytes, BoundsReadback readback) {
  // The host reads every frame's bounds. On a discrete GPU the mappable memory is uncached device
  // memory (ReBAR), which the host reads across the bus: 16 MB of a tessellated patch came back at
  // about 25 MB/s on an H200 (docs/performance.md), so 1,000 instances' boxes (32 KB) would cost
  // about 1.3 ms a frame. There the boxes are reduced in plain device memory and the frame's last
  // commands copy them into cached host memory.
  const bool first = slots_.empty();
  if (first) staged_bounds_ = readback == BoundsReadback::kStaged;
  if (!staged_bounds_) {
    ODESKIN_ASSIGN_OR_RETURN(slot.bounds,
                             vk::Buffer::create(*device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::kHostVisible));
    // The first slot's memory type decides for every slot: they all get the same one.
    if (!first || readback == BoundsReadback::kMapped || vk::hostReadsDirectly(slot.bounds.memoryFlags())) {
      return okStatus();
    }
    staged_bounds_ = true;
  }
  ODESKIN_ASSIGN_OR_RETURN(slot.bounds, vk::Buffer::create(*device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                           vk::MemoryUse::kDeviceLocalStaged));
  ODESKIN_ASSIGN_OR_RETURN(slot.bounds_readback,
                           vk::Buffer::create(*device_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::kHostReadback));
  return okStatus();
}

Status VulkanRuntime::createPipelines(const vk::FrameInputLayout& layout) {
  // One descriptor set per slot, written once: nothing is rebound per frame.
  // What every slot shares: the uploaded arrays and the folded coefficients.
  std::vector<vk::StaticBinding> statics = {{ODESKIN_BINDING_FOLDED_SERIES, folded_.handle()}};
  for (const auto& [binding, buffer] : deform_statics_) statics.push_back({binding, buffer.handle()});
  // The deformation reads all of them except the fold's own inputs (createFoldPipeline binds
  // those), the frame's inputs, and its slot's outputs.
  std::vector<std::uint32_t> shared;
  for (const vk::StaticBinding& b : statics) {
    const bool fold_only = std::ranges::find(vk::kFoldOnlyBindings, b.binding) != std::end(vk::kFoldOnlyBindings);
    if (!fold_only) shared.push_back(b.binding);
  }
  for (const vk::FrameBinding& b : layout.bindings()) shared.push_back(b.binding);
  std::vector<std::uint32_t> deform_bindings = {ODESKIN_RT_BINDING_OUT_POSITIONS, ODESKIN_RT_BINDING_BOUNDS};
  deform_bindings.insert(deform_bindings.end(), shared.begin(), shared.end());
  ODESKIN_ASSIGN_OR_RETURN(const vk::ShaderInputs inputs, vk::deformShaderInputs());
  const std::span<const std::uint32_t> deform_spirv =
      subgroup_bounds_ ? vk::deformSpirv(inputs, kInstancedDeformSpirv, kInstancedDeformStorageSpirv)
                       : vk::deformSpirv(inputs, kInstancedDeformSharedSpirv, kInstancedDeformSharedStorageSpirv);
  ODESKIN_ASSIGN_OR_RETURN(deform_,
                           vk::createSortedPipeline(*device_, deform_spirv, deform_bindings, vk::deformTexelTable(inputs),
                                                    sizeof(gpu::InstancedPushConstants), framesInFlight()));
  ODESKIN_TRY(vk::bindListed(deform_, shared, statics, layout.bindings(), ring_));
  for (std::uint32_t s = 0; s < framesInFlight(); ++s) {
    ODESKIN_TRY(deform_.bindBuffer(s, ODESKIN_RT_BINDING_OUT_POSITIONS, slots_[s].positions.handle()));
    ODESKIN_TRY(deform_.bindBuffer(s, ODESKIN_RT_BINDING_BOUNDS, slots_[s].bounds.handle()));
  }
  ODESKIN_TRY(createFoldPipeline(statics, layout));
  if (gathersRenderVertices()) ODESKIN_TRY(createGatherPipeline());
  if (options().tangents) ODESKIN_TRY(createTangentsPipeline());
  if (!options().normals) return okStatus();
  if (computesRenderNormals()) {
    ODESKIN_ASSIGN_OR_RETURN(render_normals_, createNormalsPipeline(true));
  } else {
    ODESKIN_ASSIGN_OR_RETURN(normals_, createNormalsPipeline(false));
  }
  return okStatus();
}

Result<vk::ComputePipeline> VulkanRuntime::createNormalsPipeline(bool render_vertices) const {
  const std::uint32_t bindings[] = {ODESKIN_RT_NORMALS_BINDING_POSITIONS, ODESKIN_RT_NORMALS_BINDING_CORNER_OFFSETS,
                                    ODESKIN_RT_NORMALS_BINDING_CORNERS, ODESKIN_RT_NORMALS_BINDING_OUT_NORMALS,
                                    ODESKIN_RT_NORMALS_BINDING_TOPOLOGY};
  ODESKIN_ASSIGN_OR_RETURN(vk::ComputePipeline pipeline,
                           vk::createSortedPipeline(*device_, kInstanceNormalsSpirv, bindings, vk::kNormalsTexelBindings,
                                                    sizeof(gpu::NormalsPushConstants), framesInFlight()));
  // Over the topology the shader reads no topology map (NormalsPushConstants::render_layout = 0),
  // but the binding needs a buffer: the corner offsets (uint, like the map) stand in.
  const vk::Buffer& offsets = render_vertices ? render_corner_offsets_ : corner_offsets_;
  const vk::Buffer& corners = render_vertices ? render_corners_ : corners_;
  const vk::Buffer& topology = render_vertices ? render_topology_ : corner_offsets_;
  for (std::uint32_t s = 0; s < framesInFlight(); ++s) {
    const vk::Buffer& out = render_vertices ? slots_[s].render_normals : slots_[s].normals;
    ODESKIN_TRY(pipeline.bindBuffer(s, ODESKIN_RT_NORMALS_BINDING_POSITIONS, slots_[s].positions.handle()));
    ODESKIN_TRY(pipeline.bindBuffer(s, ODESKIN_RT_NORMALS_BINDING_CORNER_OFFSETS, offsets.handle()));
    ODESKIN_TRY(pipeline.bindBuffer(s, ODESKIN_RT_NORMALS_BINDING_CORNERS, corners.handle()));
    ODESKIN_TRY(pipeline.bindBuffer(s, ODESKIN_RT_NORMALS_BINDING_OUT_NORMALS, out.handle()));
    ODESKIN_TRY(pipeline.bindBuffer(s, ODESKIN_RT_NORMALS_BINDING_TOPOLOGY, topology.handle()));
  }
  return pipeline;
}

Status VulkanRuntime::createGatherPipeline() {
  const std::uint32_t bindings[] = {ODESKIN_RT_GATHER_BINDING_POSITIONS, ODESKIN_RT_GATHER_BINDING_NORMALS,
                                    ODESKIN_RT_GATHER_BINDING_TOPOLOGY, ODESKIN_RT_GATHER_BINDING_OUT_POSITIONS,
                                    ODESKIN_RT_GATHER_BINDING_OUT_NORMALS};
  ODESKIN_ASSIGN_OR_RETURN(gather_, vk::createSortedPipeline(*device_, kRenderGatherSpirv, bindings, {},
                                                             sizeof(gpu::GatherPushConstants), framesInFlight()));
  for (std::uint32_t s = 0; s < framesInFlight(); ++s) {
    const Slot& slot = slots_[s];
    // Without normals to gather (none, or computed per render vertex across hard edges) the
    // shader reads and writes no normal (GatherPushConstants::normals = 0), but every declared
    // binding needs a buffer: the positions stand in.
    const bool normals = options().normals && !computesRenderNormals();
    ODESKIN_TRY(gather_.bindBuffer(s, ODESKIN_RT_GATHER_BINDING_POSITIONS, slot.positions.handle()));
    ODESKIN_TRY(gather_.bindBuffer(s, ODESKIN_RT_GATHER_BINDING_NORMALS,
                                   (normals ? slot.normals : slot.positions).handle()));
    ODESKIN_TRY(gather_.bindBuffer(s, ODESKIN_RT_GATHER_BINDING_TOPOLOGY, render_topology_.handle()));
    ODESKIN_TRY(gather_.bindBuffer(s, ODESKIN_RT_GATHER_BINDING_OUT_POSITIONS, slot.render_positions.handle()));
    ODESKIN_TRY(gather_.bindBuffer(s, ODESKIN_RT_GATHER_BINDING_OUT_NORMALS,
                                   (normals ? slot.render_normals : slot.render_positions).handle()));
  }
  return okStatus();
}

Status VulkanRuntime::createTangentsPipeline() {
  const std::uint32_t bindings[] = {
      ODESKIN_RT_TANGENTS_BINDING_POSITIONS, ODESKIN_RT_TANGENTS_BINDING_NORMALS, ODESKIN_RT_TANGENTS_BINDING_CORNER_OFFSETS,
      ODESKIN_RT_TANGENTS_BINDING_CORNERS,   ODESKIN_RT_TANGENTS_BINDING_TOPOLOGY, ODESKIN_RT_TANGENTS_BINDING_FRAMES,
      ODESKIN_RT_TANGENTS_BINDING_WEIGHTS,   ODESKIN_RT_TANGENTS_BINDING_OUT_TANGENTS};
  ODESKIN_ASSIGN_OR_RETURN(tangents_, vk::createSortedPipeline(*device_, kInstanceTangentsSpirv, bindings, {},
                                                               sizeof(gpu::TangentsPushConstants), framesInFlight()));
  // Without a render layout the shader reads no topology (TangentsPushConstants::render_layout =
  // 0), but the binding needs a buffer: the frames stand in.
  const vk::Buffer& topology = gathersRenderVertices() ? render_topology_ : tangent_frames_;
  for (std::uint32_t s = 0; s < framesInFlight(); ++s) {
    const Slot& slot = slots_[s];
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_POSITIONS, slot.positions.handle()));
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_NORMALS, outNormals(s).handle()));
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_CORNER_OFFSETS, corner_offsets_.handle()));
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_CORNERS, corners_.handle()));
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_TOPOLOGY, topology.handle()));
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_FRAMES, tangent_frames_.handle()));
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_WEIGHTS, tangent_weights_.handle()));
    ODESKIN_TRY(tangents_.bindBuffer(s, ODESKIN_RT_TANGENTS_BINDING_OUT_TANGENTS, slot.tangents.handle()));
  }
  return okStatus();
}

Status VulkanRuntime::createFoldPipeline(std::span<const vk::StaticBinding> statics, const vk::FrameInputLayout& layout) {
  // One folded buffer serves every slot: each frame's first barrier waits for the compute work of
  // the frames before it, so a fold never overwrites what an earlier frame's deformation reads.
  const PackedDeformData& d = asset().packed(0);
  fold_push_ = gpu::FoldPushConstants{d.modes, d.curve_count, asset().basisEntries(), 0};
  const std::uint32_t entries = d.curve_count * gpu::coefficientsPerCurve(d.modes);
  fold_groups_x_ = gpu::workgroupsFor(entries);
  ODESKIN_ASSIGN_OR_RETURN(fold_,
                           vk::createSortedPipeline(*device_, kFoldSeriesSpirv, vk::kFoldBindings, vk::kFoldTexelBindings,
                                                    sizeof(gpu::FoldPushConstants), framesInFlight()));
  return vk::bindListed(fold_, vk::kFoldBindings, statics, layout.bindings(), ring_);
}

Status VulkanRuntime::submitSlot(std::uint32_t slot, std::uint32_t instance_count, FrameTimes& times) {
  // Inputs are prepared before waiting for the slot, so this overlaps the frames still running.
  const auto start = std::chrono::steady_clock::now();
  const std::size_t bone_values = std::size_t{instance_count} * asset().boneCount();
  const std::size_t basis_values = std::size_t{instance_count} * asset().basisEntries();
  prepareInputs(std::span(records_).first(instance_count), std::span(bones_).first(bone_values),
                std::span(basis_).first(basis_values));
  times.prepare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t ring_slot, ring_.beginFrame());
  if (ring_slot != slot) {
    return internalError("vulkan runtime: frame slot " + std::to_string(slot) + " but ring slot " +
                         std::to_string(ring_slot));
  }
  // Plain copies into coherent mapped memory; the queue submit publishes them to the device.
  const std::span<std::byte> inputs = ring_.inputs(slot);
  vk::writeSlice(inputs, records_offset_, std::span<const gpu::InstanceRecord>(records_).first(instance_count));
  palettes_.write(inputs, std::span<const gpu::BoneMatrix>(bones_).first(bone_values));
  vk::writeSlice(inputs, basis_offset_, std::span<const gpu::ModeBasis>(basis_).first(basis_values));
  if (target_ != VK_NULL_HANDLE) {
    ring_.beginRecordingInto(target_);
    record(target_, slot, instance_count);
    recorded_frames_[slot] = lastFrame() + 1;
    ring_.endRecordingInto(target_, recorded_frames_[slot]);
    return okStatus();
  }
  recorded_frames_[slot] = 0;
  ODESKIN_ASSIGN_OR_RETURN(VkCommandBuffer cmd, ring_.beginRecording());
  record(cmd, slot, instance_count);
  return ring_.submit();
}

Result<std::uint64_t> VulkanRuntime::recordFrame(VkCommandBuffer cmd) {
  if (cmd == VK_NULL_HANDLE) return invalidArgument("vulkan runtime: recordFrame: the command buffer is null");
  target_ = cmd;
  Result<std::uint64_t> frame = submitFrame();
  target_ = VK_NULL_HANDLE;
  return frame;
}

Status VulkanRuntime::frameCompleted(std::uint64_t frame) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, slotOf(frame, "frameCompleted"));
  if (recorded_frames_[slot] != frame) {
    return invalidArgument("vulkan runtime: frameCompleted: frame " + std::to_string(frame) +
                           " was submitted by submitFrame(), which waits for its frames itself");
  }
  Status status = ring_.completeRecorded(slot);
  if (status.code() != StatusCode::kInvalidArgument) return status;
  return invalidArgument("vulkan runtime: frameCompleted: frame " + std::to_string(frame) +
                         " has not finished on the device (its last command has not run); call it once the "
                         "fence of the submission holding the frame has signalled");
}

Status VulkanRuntime::wait() {
  for (std::uint32_t s = 0; s < framesInFlight(); ++s) {
    if (ring_.awaitsCompletion(s)) return notCompleted(s, "wait() cannot wait for it");
  }
  return ring_.waitAll();
}

Status VulkanRuntime::waitSlot(std::uint32_t slot) {
  if (ring_.awaitsCompletion(slot)) return notCompleted(slot, "its outputs cannot be read yet");
  return ring_.waitSlot(slot);
}

Status VulkanRuntime::checkSlotFree(std::uint32_t slot) const {
  if (ring_.awaitsCompletion(slot)) {
    return notCompleted(slot, "frame " + std::to_string(lastFrame() + 1) + " needs its slot");
  }
  return okStatus();
}

Status VulkanRuntime::notCompleted(std::uint32_t slot, const std::string& what) const {
  const std::string frame = std::to_string(recorded_frames_[slot]);
  return invalidArgument("vulkan runtime: frame " + frame +
                         " was recorded into a command buffer of the engine's and is not completed (" + what +
                         "); call frameCompleted(" + frame + ") once the submission holding it has finished");
}

void VulkanRuntime::record(VkCommandBuffer cmd, std::uint32_t slot, std::uint32_t instance_count) const {
  const std::uint32_t v = asset().vertexCount();
  // The slot's previous frame may still be read (a renderer's vertex fetch, a readback copy) by
  // work submitted after it: finish those reads before this frame writes over them.
  vk::recordMemoryBarrier(cmd, reuse_stages_, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                          VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  if (instance_count == 0) return;
  // Every key 0xFFFFFFFF: above every float's key, so the first atomicMin of each workgroup wins.
  vkCmdFillBuffer(cmd, slots_[slot].bounds.handle(), 0, VkDeviceSize{instance_count} * sizeof(gpu::BoundsKeys), 0xFFFFFFFFu);
  vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  if (v > 0) {
    const PackedDeformData& d = asset().packed(0);
    gpu::InstancedPushConstants pc{};
    pc.vertex_count = v;
    pc.instance_count = instance_count;
    pc.modes = d.modes;
    pc.curve_count = d.curve_count;
    pc.material_count = d.material_count;
    pc.bone_count = d.bone_count;
    pc.influence_layout = d.influence_layout;
    pc.residual_space = d.residual_space == ResidualSpace::kBind ? ODESKIN_RESIDUAL_BIND : ODESKIN_RESIDUAL_POSED;
    pc.skinning = d.skinning == SkinningMode::kDualQuaternion ? ODESKIN_SKINNING_DUAL_QUATERNION : ODESKIN_SKINNING_LINEAR;
    pc.basis_entries = asset().basisEntries();
    // Every instance's basis folded into its own copy of the segment's coefficients first.
    dispatch(cmd, fold_, slot, &fold_push_, sizeof(fold_push_), fold_groups_x_, instance_count);
    vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    dispatch(cmd, deform_, slot, &pc, sizeof(pc), groups_x_, instance_count);
    const bool topology_normals = options().normals && !computesRenderNormals();
    if (topology_normals) {
      // Normals read neighbours' positions: every position of the frame first.
      vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
      const gpu::NormalsPushConstants npc{v, instance_count, v, 0};
      dispatch(cmd, normals_, slot, &npc, sizeof(npc), groups_x_, instance_count);
    }
    if (gathersRenderVertices()) {
      // A render vertex may copy (or, across hard edges, take the normal of) any topology vertex's
      // positions and normal: all of them first. These dispatches only read them.
      vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
      const gpu::GatherPushConstants gpc{v, outputVertexCount(), instance_count, topology_normals ? 1u : 0u};
      dispatch(cmd, gather_, slot, &gpc, sizeof(gpc), render_groups_x_, instance_count);
      if (computesRenderNormals()) {
        const gpu::NormalsPushConstants npc{outputVertexCount(), instance_count, v, 1};
        dispatch(cmd, render_normals_, slot, &npc, sizeof(npc), render_groups_x_, instance_count);
      }
    }
    if (options().tangents) {
      // A tangent reads its one-ring's positions and its output vertex's normal (gathered or
      // computed just above): all of them first.
      vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
      const gpu::TangentsPushConstants tpc{v, outputVertexCount(), instance_count, gathersRenderVertices() ? 1u : 0u};
      dispatch(cmd, tangents_, slot, &tpc, sizeof(tpc), gpu::workgroupsFor(outputVertexCount()), instance_count);
    }
  }
  VkPipelineStageFlags written_by = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  VkAccessFlags writes = VK_ACCESS_SHADER_WRITE_BIT;
  if (staged_bounds_) {
    vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferCopy region{0, 0, VkDeviceSize{instance_count} * sizeof(gpu::BoundsKeys)};
    vkCmdCopyBuffer(cmd, slots_[slot].bounds.handle(), slots_[slot].bounds_readback.handle(), 1, &region);
    written_by |= VK_PIPELINE_STAGE_TRANSFER_BIT;
    writes |= VK_ACCESS_TRANSFER_WRITE_BIT;
  }
  // A fence alone does not make device writes visible to the host (bounds and mapped outputs).
  vk::recordMemoryBarrier(cmd, written_by, writes, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

Result<RuntimeFrameBuffers> VulkanRuntime::frameBuffers(std::uint64_t frame) const {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, slotOf(frame, "frameBuffers"));
  RuntimeFrameBuffers b;
  b.positions = outPositions(slot).handle();
  b.normals = options().normals ? outNormals(slot).handle() : VK_NULL_HANDLE;
  b.tangents = options().tangents ? slots_[slot].tangents.handle() : VK_NULL_HANDLE;
  b.instance_stride = VkDeviceSize{outputVertexCount()} * sizeof(gpu::Float4);
  return b;
}

Result<RuntimeOutputBarriers> VulkanRuntime::outputBarriers(std::uint64_t frame) const {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, slotOf(frame, "outputBarriers"));
  RuntimeOutputBarriers b;
  b.barriers[b.count++] = vertexInputBarrier(outPositions(slot).handle());
  if (options().normals) b.barriers[b.count++] = vertexInputBarrier(outNormals(slot).handle());
  if (options().tangents) b.barriers[b.count++] = vertexInputBarrier(slots_[slot].tangents.handle());
  return b;
}

const vk::Buffer& VulkanRuntime::outPositions(std::uint32_t slot) const {
  return gathersRenderVertices() ? slots_[slot].render_positions : slots_[slot].positions;
}

const vk::Buffer& VulkanRuntime::outNormals(std::uint32_t slot) const {
  return gathersRenderVertices() ? slots_[slot].render_normals : slots_[slot].normals;
}

Status VulkanRuntime::copyInstance(const vk::Buffer& buffer, std::uint32_t instance, std::span<gpu::Float4> out) {
  const VkDeviceSize offset = VkDeviceSize{instance} * outputVertexCount() * sizeof(gpu::Float4);
  if (readback_) return readback_->download(*device_, buffer, std::as_writable_bytes(out), offset);
  return vk::downloadSpan(*device_, buffer, out, offset);
}

Status VulkanRuntime::copyPositions(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) {
  return copyInstance(outPositions(slot), instance, out);
}

Status VulkanRuntime::copyNormals(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) {
  return copyInstance(outNormals(slot), instance, out);
}

Status VulkanRuntime::copyTangents(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) {
  return copyInstance(slots_[slot].tangents, instance, out);
}

Status VulkanRuntime::copyBounds(std::uint32_t slot, std::span<InstanceBounds> out) {
  const vk::Buffer& readable = staged_bounds_ ? slots_[slot].bounds_readback : slots_[slot].bounds;
  const std::byte* keys = readable.mapped();
  if (keys == nullptr) return internalError("vulkan runtime: the bounds buffer is not mapped");
  for (std::size_t k = 0; k < out.size(); ++k) {
    gpu::BoundsKeys entry;
    std::memcpy(&entry, keys + k * sizeof(gpu::BoundsKeys), sizeof(entry));
    out[k] = decodeBounds(entry);
  }
  return okStatus();
}

}  // namespace odeskin
