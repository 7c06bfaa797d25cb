// SPDX-License-Identifier: MIT
#include "gpu_deformer.hpp"

#include <string>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "shaders/fourier_deform.spv.h"
#include "shaders/fourier_deform_storage.spv.h"

namespace odeskin {
namespace {

template <typename T>
std::span<const std::byte> bytesOf(const std::vector<T>& v) {
  return std::as_bytes(std::span<const T>(v));
}

}  // namespace

Result<GpuDeformer> GpuDeformer::create(const vk::Device& device, const PackedDeformData& data) {
  // The CPU job's own checks on the packed arrays, so both paths accept exactly the same data.
  {
    std::vector<gpu::BoneMatrix> bones(data.bone_count);
    std::vector<gpu::ModeBasis> basis(ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes}));
    std::vector<gpu::Float4> out(data.vertex_count);
    FourierDeformFastJob job;
    job.data = &data;
    job.segment = 0;
    job.bones = bones;
    job.basis = basis;
    job.out_positions = out;
    ODESKIN_TRY(job.validate());
  }

  GpuDeformer deformer;
  deformer.segment_count_ = data.segment_count;
  deformer.bone_count_ = data.bone_count;
  deformer.basis_count_ = ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes});
  for (std::uint32_t s = 0; s < data.segment_count; ++s) {
    deformer.push_constants_.push_back(deformPushConstants(data, s));
  }

  // Uploaded once, read every frame: device-local (mapped on lavapipe/ReBAR, staged elsewhere).
  struct Array {
    std::uint32_t binding;
    std::span<const std::byte> bytes;
  };
  const Array arrays[] = {
      {ODESKIN_BINDING_REST_POSITIONS, bytesOf(data.rest_positions)},
      {ODESKIN_BINDING_VERTEX_BINDINGS, bytesOf(data.bindings)},
      {ODESKIN_BINDING_SEGMENT_VERTICES, bytesOf(data.segment_vertices)},
      {ODESKIN_BINDING_REMAINDERS, bytesOf(data.remainders)},
      {ODESKIN_BINDING_CURVE_MATERIALS, bytesOf(data.curve_materials)},
      {ODESKIN_BINDING_COEFFICIENTS, bytesOf(data.coefficients)},
      {ODESKIN_BINDING_RATES, bytesOf(data.rates)},
      {ODESKIN_BINDING_INFLUENCE_OFFSETS, bytesOf(data.influence_offsets)},
      {ODESKIN_BINDING_INFLUENCES, bytesOf(data.influences)},
  };
  std::vector<vk::StaticBinding> statics;
  for (const Array& array : arrays) {
    ODESKIN_ASSIGN_OR_RETURN(vk::Buffer buffer, vk::createStorageBuffer(device, array.bytes));
    statics.push_back({array.binding, buffer.handle()});
    deformer.inputs_.push_back(std::move(buffer));
  }

  SingleMeshDispatchDesc desc;
  desc.name = "fourier deform gpu";
  desc.spirv = kFourierDeformSpirv;
  desc.storage_spirv = kFourierDeformStorageSpirv;
  desc.vertex_count = data.vertex_count;
  desc.bone_count = data.bone_count;
  desc.skinning = data.skinning;
  desc.basis_count = deformer.basis_count_;
  desc.statics = statics;
  desc.push_constant_bytes = sizeof(gpu::DeformPushConstants);
  desc.fold_series = true;
  desc.modes = data.modes;
  desc.curve_count = data.curve_count;
  ODESKIN_ASSIGN_OR_RETURN(deformer.dispatch_, SingleMeshDispatch::create(device, desc));
  return deformer;
}

Status GpuDeformer::validate(const GpuDeformFrame& frame) const {
  // Same checks and messages as FourierDeformFastJob::validate, per-frame fields only (the packed
  // arrays were checked by create()).
  if (frame.segment >= segment_count_) {
    return invalidArgument("fourier deform gpu: segment " + std::to_string(frame.segment) + " of " +
                           std::to_string(segment_count_));
  }
  if (frame.bones.size() != bone_count_) {
    return invalidArgument("fourier deform gpu: bones has " + std::to_string(frame.bones.size()) +
                           " entries, expected " + std::to_string(bone_count_));
  }
  if (frame.basis.size() != basis_count_) {
    return invalidArgument("fourier deform gpu: basis has " + std::to_string(frame.basis.size()) +
                           " entries, expected material_count x (N+1) + 1 = " + std::to_string(basis_count_));
  }
  return okStatus();
}

Status GpuDeformer::submit(const GpuDeformFrame& frame) {
  ODESKIN_TRY(validate(frame));
  const gpu::DeformPushConstants& push = push_constants_[frame.segment];
  return dispatch_.submit(frame.bones, frame.basis, &push, frame.segment, push.use_rates != 0);
}

Status GpuDeformer::run(const GpuDeformFrame& frame) {
  ODESKIN_TRY(submit(frame));
  return wait();
}

}  // namespace odeskin
