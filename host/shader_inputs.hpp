// SPDX-License-Identifier: MIT
// How the deformation shaders (fourier_deform.comp, lbs.comp, instanced_deform*.comp) read their
// inputs: uniform texel buffers (the default), or storage buffers (ODESKIN_SHADER_INPUTS=storage).
// Lavapipe gathers a texel per lane but loads a storage buffer component by component, and runs the
// storage builds about 5x slower (odeskin 5.9x, LBS 4.8x at 32,185 vertices). On an H200 the texel
// builds' GPU time grows with their fetch count as if the texture units set the pace, which the
// storage builds would avoid; they have not yet run on a GPU, so they stay opt-in until one
// measures them (docs/performance.md, "On a GPU"). shaders/deform_inputs.glsl builds both.
#pragma once

#include <span>

#include "compute_pipeline.hpp"
#include "engine/core/result.hpp"

namespace odeskin::vk {

enum class ShaderInputs { kTexel, kStorage };

// Texel buffers unless the environment's ODESKIN_SHADER_INPUTS says texel or storage (the tests run
// both on lavapipe; `odeskin bench` records which ran). kInvalidArgument for another value.
Result<ShaderInputs> deformShaderInputs();

// The texel-buffer table a deformation pipeline sorts its bindings by: kDeformTexelBindings, or
// none (every binding a storage buffer).
std::span<const TexelBinding> deformTexelTable(ShaderInputs inputs);

// The build of a deformation shader for `inputs`.
inline std::span<const std::uint32_t> deformSpirv(ShaderInputs inputs, std::span<const std::uint32_t> texel,
                                                  std::span<const std::uint32_t> storage) {
  return inputs == ShaderInputs::kStorage ? storage : texel;
}

}  // namespace odeskin::vk
