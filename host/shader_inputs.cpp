// SPDX-License-Identifier: MIT
#include "shader_inputs.hpp"

#include <cstdlib>
#include <string>

#include "texel_bindings.hpp"

namespace odeskin::vk {

Result<ShaderInputs> deformShaderInputs() {
  if (const char* value = std::getenv("ODESKIN_SHADER_INPUTS"); value != nullptr && *value != '\0') {
    const std::string text = value;
    if (text == "texel") return ShaderInputs::kTexel;
    if (text == "storage") return ShaderInputs::kStorage;
    return invalidArgument("ODESKIN_SHADER_INPUTS=" + text + ": expected texel or storage");
  }
  return ShaderInputs::kTexel;
}

std::span<const TexelBinding> deformTexelTable(ShaderInputs inputs) {
  if (inputs == ShaderInputs::kStorage) return {};
  return kDeformTexelBindings;
}

}  // namespace odeskin::vk
