// SPDX-License-Identifier: MIT
#include "single_mesh_dispatch.hpp"

#include <iterator>
#include <vector>

#include "engine/runtime/runtime_layout.hpp"
#include "shader_inputs.hpp"
#include "shaders/fold_series.spv.h"
#include "texel_bindings.hpp"

namespace odeskin {
namespace {

// Bindings only the fold reads: its inputs no deformation shader declares, and the frame's record
// (a single mesh's shader takes its segment from the push constants).
constexpr std::uint32_t kSingleMeshFoldOnly[] = {ODESKIN_BINDING_CURVE_MATERIALS, ODESKIN_BINDING_COEFFICIENTS,
                                                 ODESKIN_BINDING_RATES, ODESKIN_RT_BINDING_INSTANCES};
static_assert(std::size(kSingleMeshFoldOnly) == std::size(vk::kFoldOnlyBindings) + 1);

}  // namespace

Result<SingleMeshDispatch> SingleMeshDispatch::create(const vk::Device& device, const SingleMeshDispatchDesc& desc) {
  SingleMeshDispatch d;
  d.device_ = &device;
  d.name_ = desc.name;
  d.vertex_count_ = desc.vertex_count;
  // The output doubles as a vertex buffer and a copy source (readback on non-mappable memory).
  const VkDeviceSize out_bytes = static_cast<VkDeviceSize>(desc.vertex_count) * sizeof(gpu::Float4);
  ODESKIN_ASSIGN_OR_RETURN(d.out_positions_,
                           vk::Buffer::create(device, out_bytes < 16 ? 16 : out_bytes, vk::kOutputBufferUsage));
  std::vector<vk::StaticBinding> statics(desc.statics.begin(), desc.statics.end());
  statics.push_back({ODESKIN_BINDING_OUT_POSITIONS, d.out_positions_.handle()});
  // One folded buffer serves every frame: each frame's barrier before its first dispatch waits for
  // the compute work of the frames before it, so a fold never overwrites what a deformation reads.
  const std::uint32_t fold_entries = desc.curve_count * gpu::coefficientsPerCurve(desc.modes);
  if (desc.fold_series) {
    const VkDeviceSize fold_bytes = VkDeviceSize{fold_entries} * sizeof(gpu::Float4);
    ODESKIN_ASSIGN_OR_RETURN(d.folded_, vk::Buffer::create(device, fold_bytes < 16 ? 16 : fold_bytes, vk::kShaderInputUsage));
    statics.push_back({ODESKIN_BINDING_FOLDED_SERIES, d.folded_.handle()});
    d.fold_push_ = gpu::FoldPushConstants{desc.modes, desc.curve_count, static_cast<std::uint32_t>(desc.basis_count), 0};
    d.fold_groups_ = gpu::workgroupsFor(fold_entries);
  }

  // Per-frame buffer: bones, the basis (when read), then the bones' dual quaternions.
  vk::FrameInputLayout layout(device);
  d.palettes_ = vk::BonePaletteWriter::plan(layout, ODESKIN_BINDING_BONES, ODESKIN_BINDING_BONE_DUAL_QUATS,
                                            desc.bone_count, desc.skinning);
  if (desc.basis_count > 0) d.basis_offset_ = layout.add(ODESKIN_BINDING_MODE_BASIS, desc.basis_count * sizeof(gpu::ModeBasis));
  if (desc.fold_series) d.record_offset_ = layout.add(ODESKIN_RT_BINDING_INSTANCES, sizeof(gpu::InstanceRecord));
  ODESKIN_TRY(layout.checkLimits(desc.name.c_str()));

  ODESKIN_ASSIGN_OR_RETURN(const vk::ShaderInputs inputs, vk::deformShaderInputs());
  vk::ComputeDispatcherDesc dispatcher;
  dispatcher.spirv = vk::deformSpirv(inputs, desc.spirv, desc.storage_spirv);
  dispatcher.static_bindings = statics;
  dispatcher.frame_bindings = layout.bindings();
  dispatcher.texel_bindings = vk::deformTexelTable(inputs);
  dispatcher.frame_bytes = layout.totalBytes();
  dispatcher.push_constant_bytes = desc.push_constant_bytes;
  dispatcher.frames_in_flight = 2;
  vk::ComputePrepassDesc fold;
  fold.spirv = kFoldSeriesSpirv;
  fold.bindings = vk::kFoldBindings;
  fold.texel_bindings = vk::kFoldTexelBindings;
  fold.push_constant_bytes = sizeof(gpu::FoldPushConstants);
  fold.prepass_only = kSingleMeshFoldOnly;
  if (desc.fold_series) dispatcher.prepass = &fold;
  ODESKIN_ASSIGN_OR_RETURN(d.dispatcher_, vk::ComputeDispatcher::create(device, dispatcher));
  return d;
}

Status SingleMeshDispatch::submit(std::span<const gpu::BoneMatrix> bones, std::span<const gpu::ModeBasis> basis,
                                  const void* push, std::uint32_t segment, bool use_rates) {
  if (vertex_count_ == 0) return okStatus();
  ODESKIN_ASSIGN_OR_RETURN(std::span<std::byte> inputs, dispatcher_.beginFrame());
  // Plain copies into coherent mapped memory; the queue submit publishes them to the device.
  palettes_.write(inputs, bones);
  vk::writeSlice(inputs, basis_offset_, basis);
  if (fold_groups_ > 0) {
    // One deformation: its record gives the fold the segment and whether it has rates.
    const gpu::InstanceRecord record{segment, 0, use_rates ? 0u : gpu::kNoRates, 0};
    vk::writeSlice(inputs, record_offset_, std::span<const gpu::InstanceRecord>(&record, 1));
  }
  return dispatcher_.submitFrame(push, gpu::workgroupsFor(vertex_count_), &fold_push_, fold_groups_);
}

Status SingleMeshDispatch::readPositions(std::span<gpu::Float4> out_positions) {
  if (out_positions.size() != vertex_count_) {
    return invalidArgument(name_ + ": out_positions has " + std::to_string(out_positions.size()) +
                           " entries, expected " + std::to_string(vertex_count_));
  }
  ODESKIN_TRY(wait());
  return vk::downloadSpan(*device_, out_positions_, out_positions);
}

OutputBarrier SingleMeshDispatch::outputBarrier() const {
  OutputBarrier result;
  result.barrier = vertexInputBarrier(out_positions_.handle());
  return result;
}

}  // namespace odeskin
