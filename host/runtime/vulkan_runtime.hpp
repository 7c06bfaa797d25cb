// SPDX-License-Identifier: MIT
// The runtime on Vulkan compute (DeformRuntime's API, issue 6 point 1). The asset is uploaded once;
// each submitFrame() writes every instance's inputs (InstanceRecord, bones, time basis; runtime_layout.h)
// into the next slot of a FrameRing and records ONE command buffer: reset the slot's bounds, one
// dispatch of fold_series.comp that folds every instance's time basis into its copy of the curve
// coefficients, ONE dispatch of instanced_deform.comp over (ceil(V / 64), instances) workgroups that
// deforms all instances into the slot's output buffer (instance k at k * V) and reduces their
// boxes, then one dispatch of instance_normals.comp (and, with RuntimeOptions::render_layout on a
// glTF asset, one of render_gather.comp into the render vertices; with RuntimeOptions::tangents,
// one of instance_tangents.comp). framesInFlight() slots
// (default 2) each own their outputs, so the host prepares frame k+1 and a renderer draws frame k
// while the GPU deforms. No allocation per frame (readbacks from non-mappable memory stage through
// a temporary buffer, on request only).
// recordFrame() records the same commands into a command buffer of the engine's instead.
// Reference: CpuRuntime, instance for instance (tests/runtime/vulkan_runtime_test.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/runtime/deform_runtime.hpp"
#include "host/buffer.hpp"
#include "host/compute_dispatcher.hpp"
#include "host/compute_pipeline.hpp"
#include "host/device.hpp"
#include "host/frame_inputs.hpp"
#include "host/frame_ring.hpp"
#include "host/output_barrier.hpp"

namespace odeskin {

// What a renderer needs to draw a frame's instances straight from the deformer's buffers.
struct RuntimeFrameBuffers {
  VkBuffer positions = VK_NULL_HANDLE;  // Float4 xyz1 per vertex, instance k at k * instance_stride bytes
  VkBuffer normals = VK_NULL_HANDLE;    // Float4 xyz0 per vertex, same layout; null with normals off
  VkBuffer tangents = VK_NULL_HANDLE;   // Float4 xyz + handedness per vertex, same layout; null with tangents off
  VkDeviceSize instance_stride = 0;     // outputVertexCount() * 16 bytes
};

// The barriers a renderer records (same queue, after submitFrame's submission, before the draws)
// so vertex fetch sees the frame's compute writes: one per output buffer.
struct RuntimeOutputBarriers {
  VkPipelineStageFlags src_stage = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  VkPipelineStageFlags dst_stage = VK_PIPELINE_STAGE_VERTEX_INPUT_BIT;
  std::array<VkBufferMemoryBarrier, 3> barriers{};
  std::uint32_t count = 0;

  void record(VkCommandBuffer cmd) const {
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, count, barriers.data(), 0, nullptr);
  }
};

// How the host reads each frame's bounds.
enum class BoundsReadback {
  kAuto,    // kMapped where the bounds' host-visible memory is cached for the host, else kStaged
  kMapped,  // the bounds buffer's own mapping, whatever its memory (a discrete GPU's is uncached)
  kStaged,  // the frame's last commands copy the bounds into cached host memory
};

// Choices a caller normally leaves to the device (tests and benchmarks force the other path).
struct VulkanRuntimePaths {
  // False forces the shared-memory bounds reduction even where subgroup arithmetic exists.
  bool allow_subgroups = true;
  BoundsReadback bounds = BoundsReadback::kAuto;
};

class VulkanRuntime final : public DeformRuntime {
 public:
  // `device` and `asset` must outlive the runtime and stay where they are. kInvalidArgument for
  // frames_in_flight = 0; kUnavailable, naming the limit, when capacity exceeds
  // maxComputeWorkGroupCount[1], ceil(V / 64) exceeds maxComputeWorkGroupCount[0], or one frame's
  // outputs (capacity x V x 16 bytes; with render_layout, or tangents, also capacity x R x 16), folded
  // coefficients (capacity x C x (2N + 2) x 16 bytes) or inputs exceed maxStorageBufferRange (lavapipe: 128 MiB, i.e. about 8.4 million instance
  // vertices per runtime; use several runtimes beyond);
  // kDeviceError from the driver.
  static Result<VulkanRuntime> create(const vk::Device& device, const RuntimeAsset& asset,
                                      const RuntimeOptions& options, VulkanRuntimePaths paths = {});

  VulkanRuntime(VulkanRuntime&&) noexcept = default;
  // Not assignable: the old runtime's frames would have to finish first; hold runtimes by value
  // or pointer instead.
  VulkanRuntime& operator=(VulkanRuntime&&) = delete;
  ~VulkanRuntime() override = default;

  std::string_view backendName() const override { return "vulkan"; }
  // kInvalidArgument, naming it, while a recorded frame is not completed (it cannot wait for those).
  Status wait() override;
  RuntimeMemory memory() const override;

  // Instead of submitFrame(): the frame recorded into `cmd`, a primary command buffer of the
  // engine's in the recording state, outside a render pass, from a pool of the device's queue
  // family, to be submitted with the engine's own work. Returns the frame's number; readers and
  // outputBarriers() take it as for a submitted frame. The contract, which the runtime cannot see:
  // - the engine submits `cmd` on the device's queue (vk::Device::queue()), and frames in the order
  //   they were recorded, after the inputs written here (host writes before the submission);
  // - once that submission has finished (its fence), it calls frameCompleted(frame). Until then the
  //   frame cannot be read, and the frame framesInFlight() later cannot take its slot: both are
  //   kInvalidArgument naming the frame, never a wait that could not end.
  // On error nothing is recorded into `cmd`. A runtime destroyed with recorded frames not completed
  // waits for the device's queue to idle first, so their submissions never outlive its buffers.
  Result<std::uint64_t> recordFrame(VkCommandBuffer cmd);
  // The engine's word that the submission holding recorded frame `frame` has finished; reads the
  // frame's GPU time. The frame's last command writes its number to host-visible memory, so a call
  // before it has run (the submission is still running, or was never made) is refused
  // (kInvalidArgument) rather than taken on trust. Completing a frame twice is harmless; a frame
  // submitFrame() submitted, or one not held, is kInvalidArgument.
  Status frameCompleted(std::uint64_t frame);

  // `frame`'s buffers, without waiting (kInvalidArgument for a frame not held). Valid until its
  // slot is reused, framesInFlight() submissions later.
  Result<RuntimeFrameBuffers> frameBuffers(std::uint64_t frame) const;
  Result<RuntimeOutputBarriers> outputBarriers(std::uint64_t frame) const;
  // True when the bounds are reduced with subgroup operations (instanced_deform.comp), false on
  // devices without subgroup arithmetic in compute (instanced_deform_shared.comp).
  bool subgroupBounds() const { return subgroup_bounds_; }
  // True when each frame ends by copying its bounds into cached host memory (BoundsReadback's
  // kStaged, chosen or forced); false when readBounds() reads the bounds buffer's mapping.
  bool stagedBounds() const { return staged_bounds_; }

 protected:
  Status submitSlot(std::uint32_t slot, std::uint32_t instance_count, FrameTimes& times) override;
  Status waitSlot(std::uint32_t slot) override;
  Status checkSlotFree(std::uint32_t slot) const override;
  Status copyPositions(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) override;
  Status copyNormals(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) override;
  Status copyTangents(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) override;
  Status copyBounds(std::uint32_t slot, std::span<InstanceBounds> out) override;
  double deviceSeconds(std::uint32_t slot) const override { return ring_.gpuSeconds(slot); }

 private:
  VulkanRuntime(const RuntimeAsset& asset, const RuntimeOptions& options) : DeformRuntime(asset, options) {}
  Status uploadAsset();
  Status createSlots(BoundsReadback bounds);
  // One instance's Float4 output from `buffer`: through readback_ where it exists, else download().
  Status copyInstance(const vk::Buffer& buffer, std::uint32_t instance, std::span<gpu::Float4> out);
  Status createPipelines(const vk::FrameInputLayout& layout);
  // `statics`: the buffers every slot shares (createPipelines' list).
  Status createFoldPipeline(std::span<const vk::StaticBinding> statics, const vk::FrameInputLayout& layout);
  void record(VkCommandBuffer cmd, std::uint32_t slot, std::uint32_t instance_count) const;
  Status createGatherPipeline();
  Status createTangentsPipeline();
  // instance_normals.comp over the topology's corners into `out` (slots' topology normals), or over
  // the render vertices' (hard edges) into the slots' render normals; one set per slot.
  Result<vk::ComputePipeline> createNormalsPipeline(bool render_vertices) const;
  // What the renderer reads: the render-vertex buffers when gathering, else the topology's.
  const vk::Buffer& outPositions(std::uint32_t slot) const;
  const vk::Buffer& outNormals(std::uint32_t slot) const;
  // kInvalidArgument telling the engine to complete `slot`'s recorded frame first.
  Status notCompleted(std::uint32_t slot, const std::string& what) const;

  struct Slot {
    vk::Buffer positions;         // capacity x V Float4
    vk::Buffer normals;           // likewise, when normals are on (and not computesRenderNormals())
    vk::Buffer bounds;            // capacity BoundsKeys: host-visible, or device-local when staged_bounds_
    vk::Buffer bounds_readback;   // the frame's copy of bounds in cached host memory, when staged_bounds_
    vk::Buffer render_positions;  // capacity x R Float4, when gathersRenderVertices()
    vk::Buffer render_normals;    // likewise, when normals are on too
    vk::Buffer tangents;          // capacity x outputVertexCount() Float4, when tangents are on
  };
  // The slot's bounds buffer, and its readback buffer when the bounds are staged.
  Status createBounds(Slot& slot, VkDeviceSize bytes, BoundsReadback readback);
  const vk::Device* device_ = nullptr;
  VkPipelineStageFlags reuse_stages_ = 0;
  std::uint32_t groups_x_ = 0;       // ceil(V / 64)
  std::uint32_t fold_groups_x_ = 0;  // ceil(C (2N + 2) / 64)
  gpu::FoldPushConstants fold_push_{};
  bool subgroup_bounds_ = false;
  bool staged_bounds_ = false;
  // Host copies of one frame's inputs, prepared before waiting for the slot, then copied in.
  std::vector<gpu::InstanceRecord> records_;
  std::vector<gpu::BoneMatrix> bones_;
  std::vector<gpu::ModeBasis> basis_;
  VkDeviceSize records_offset_ = 0;
  VkDeviceSize basis_offset_ = 0;
  vk::BonePaletteWriter palettes_;
  std::vector<std::pair<std::uint32_t, vk::Buffer>> deform_statics_;  // (binding, asset array), uploaded once
  vk::Buffer corner_offsets_;  // normals: RuntimeAsset::cornerOffsets
  vk::Buffer corners_;         // normals: RuntimeAsset::corners
  std::vector<Slot> slots_;
  // Per slot, the frame recordFrame() put there (0: submitted by submitFrame()). recordFrame sets
  // target_ to the engine's command buffer for the duration of its submitFrame().
  std::vector<std::uint64_t> recorded_frames_;
  VkCommandBuffer target_ = VK_NULL_HANDLE;
  vk::Buffer folded_;  // capacity x C x (2N + 2) Float4: fold_series.comp's output, shared by the slots
  std::optional<vk::ReadbackStage> readback_;  // the copy calls' staging, where outputs are not read in place
  vk::ComputePipeline fold_;
  vk::ComputePipeline deform_;
  vk::ComputePipeline normals_;         // over the topology, when normals are on and not computesRenderNormals()
  vk::ComputePipeline render_normals_;  // over the render vertices, when computesRenderNormals()
  vk::Buffer render_corner_offsets_;    // RuntimeAsset::renderCornerOffsets, likewise
  vk::Buffer render_corners_;           // RuntimeAsset::renderCorners, likewise
  vk::ComputePipeline gather_;   // render_gather.comp, when gathersRenderVertices()
  vk::Buffer render_topology_;   // RuntimeAsset::renderTopology, likewise
  std::uint32_t render_groups_x_ = 0;  // ceil(R / 64)
  vk::ComputePipeline tangents_;  // instance_tangents.comp, when options().tangents
  vk::Buffer tangent_frames_;     // RuntimeAsset::tangentFrames, likewise
  vk::Buffer tangent_weights_;    // RuntimeAsset::tangentWeights, likewise
  // Last, so it is destroyed first: it waits for in-flight frames before anything they use goes.
  vk::FrameRing ring_;
};

}  // namespace odeskin
