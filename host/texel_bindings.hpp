// SPDX-License-Identifier: MIT
// Which read-only shader inputs are uniform texel buffers, and the texel each texelFetch returns:
// the deformation shaders' (fourier_deform.comp, lbs.comp, instanced_deform*.comp; gpu_layout.h and
// runtime_layout.h bindings, which share their numbers), fold_series.comp's and
// instance_normals.comp's. Outputs and
// the bounds (written, atomics) stay storage buffers. Structs of mixed uint and float fields are
// fetched as uint texels and the floats taken back with uintBitsToFloat.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "compute_pipeline.hpp"
#include "engine/runtime/runtime_layout.h"

namespace odeskin::vk {

static_assert(ODESKIN_RT_BINDING_BONES == ODESKIN_BINDING_BONES && ODESKIN_RT_BINDING_MODE_BASIS == ODESKIN_BINDING_MODE_BASIS &&
                  ODESKIN_RT_BINDING_BONE_DUAL_QUATS == ODESKIN_BINDING_BONE_DUAL_QUATS,
              "one table serves the single-mesh and the instanced shaders");
static_assert(ODESKIN_BINDING_FOLDED_SERIES != ODESKIN_RT_BINDING_INSTANCES &&
                  ODESKIN_BINDING_FOLDED_SERIES != ODESKIN_RT_BINDING_BOUNDS,
              "the folded coefficients have a binding of their own in both layouts");

inline constexpr TexelBinding kDeformTexelBindings[] = {
    {ODESKIN_BINDING_REST_POSITIONS, VK_FORMAT_R32G32B32A32_SFLOAT},    // Float4
    {ODESKIN_BINDING_VERTEX_BINDINGS, VK_FORMAT_R32G32B32A32_UINT},     // VertexBinding
    {ODESKIN_BINDING_SEGMENT_VERTICES, VK_FORMAT_R32G32B32A32_UINT},    // SegmentVertex
    {ODESKIN_BINDING_REMAINDERS, VK_FORMAT_R32G32B32A32_SFLOAT},        // Float4
    {ODESKIN_BINDING_INFLUENCE_OFFSETS, VK_FORMAT_R32_UINT},            // uint
    {ODESKIN_BINDING_INFLUENCES, VK_FORMAT_R32G32_UINT},                // Influence
    {ODESKIN_BINDING_BONES, VK_FORMAT_R32G32B32A32_SFLOAT},             // BoneMatrix: 3 texels (rows)
    {ODESKIN_BINDING_MODE_BASIS, VK_FORMAT_R32G32_SFLOAT},              // ModeBasis
    {ODESKIN_BINDING_BONE_DUAL_QUATS, VK_FORMAT_R32G32B32A32_SFLOAT},   // DualQuat: 2 texels (real, dual)
    {ODESKIN_RT_BINDING_INSTANCES, VK_FORMAT_R32G32B32A32_UINT},        // InstanceRecord
    {ODESKIN_BINDING_FOLDED_SERIES, VK_FORMAT_R32G32B32A32_SFLOAT},     // Float4 (fold_series.comp's output)
};

// fold_series.comp's inputs; its output, ODESKIN_BINDING_FOLDED_SERIES, is a storage buffer there.
inline constexpr TexelBinding kFoldTexelBindings[] = {
    {ODESKIN_BINDING_CURVE_MATERIALS, VK_FORMAT_R32_UINT},          // uint
    {ODESKIN_BINDING_COEFFICIENTS, VK_FORMAT_R32G32B32A32_SFLOAT},  // Float4
    {ODESKIN_BINDING_RATES, VK_FORMAT_R32G32B32A32_SFLOAT},         // Float4
    {ODESKIN_BINDING_MODE_BASIS, VK_FORMAT_R32G32_SFLOAT},          // ModeBasis
    {ODESKIN_RT_BINDING_INSTANCES, VK_FORMAT_R32G32B32A32_UINT},    // InstanceRecord
};
// The bindings fold_series.comp declares, in the order of kFoldTexelBindings, then its output.
inline constexpr std::uint32_t kFoldBindings[] = {ODESKIN_BINDING_CURVE_MATERIALS, ODESKIN_BINDING_COEFFICIENTS,
                                                  ODESKIN_BINDING_RATES,           ODESKIN_BINDING_MODE_BASIS,
                                                  ODESKIN_RT_BINDING_INSTANCES,    ODESKIN_BINDING_FOLDED_SERIES};
// The fold's inputs that no deformation shader declares (they read the folded products instead):
// left out of the deformation pipelines' layouts.
inline constexpr std::uint32_t kFoldOnlyBindings[] = {ODESKIN_BINDING_CURVE_MATERIALS, ODESKIN_BINDING_COEFFICIENTS,
                                                      ODESKIN_BINDING_RATES};

inline constexpr TexelBinding kNormalsTexelBindings[] = {
    {ODESKIN_RT_NORMALS_BINDING_POSITIONS, VK_FORMAT_R32G32B32A32_SFLOAT},  // Float4
    {ODESKIN_RT_NORMALS_BINDING_CORNER_OFFSETS, VK_FORMAT_R32_UINT},        // uint
    {ODESKIN_RT_NORMALS_BINDING_CORNERS, VK_FORMAT_R32G32_UINT},            // Corner
    {ODESKIN_RT_NORMALS_BINDING_TOPOLOGY, VK_FORMAT_R32_UINT},              // uint
};

// A pipeline's bindings sorted into ComputePipelineDesc's two lists: those `table` names are texel
// buffers (with its format), the others storage buffers.
struct SortedBindings {
  std::vector<std::uint32_t> storage;
  std::vector<TexelBinding> texels;

  static SortedBindings sort(std::span<const std::uint32_t> bindings, std::span<const TexelBinding> table) {
    SortedBindings result;
    for (std::uint32_t binding : bindings) {
      bool texel = false;
      for (const TexelBinding& t : table) {
        if (t.binding != binding) continue;
        result.texels.push_back(t);
        texel = true;
        break;
      }
      if (!texel) result.storage.push_back(binding);
    }
    return result;
  }
};

// A compute pipeline whose set 0 holds `bindings`: those `table` names as uniform texel buffers, the
// others as storage buffers; `set_count` descriptor sets (ComputePipeline::create's errors).
inline Result<ComputePipeline> createSortedPipeline(const Device& device, std::span<const std::uint32_t> spirv,
                                                    std::span<const std::uint32_t> bindings,
                                                    std::span<const TexelBinding> table,
                                                    std::uint32_t push_constant_bytes, std::uint32_t set_count) {
  const SortedBindings sorted = SortedBindings::sort(bindings, table);
  ComputePipelineDesc desc;
  desc.spirv = spirv;
  desc.storage_bindings = sorted.storage;
  desc.texel_bindings = sorted.texels;
  desc.push_constant_bytes = push_constant_bytes;
  desc.descriptor_set_count = set_count;
  return ComputePipeline::create(device, desc);
}

}  // namespace odeskin::vk
