// SPDX-License-Identifier: MIT
// The baked form of `odeskin export`: the player's frames (double-precision reference) in the
// asset's output layout, one morph target per frame, LINEAR cross-fades between frames; quantized
// (KHR_mesh_quantization) when asked.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "../core/result.hpp"
#include "../io/gltf_baked_writer.hpp"
#include "../io/gltf_materials.hpp"
#include "../offline/deform_player.hpp"

namespace odeskin {

struct BakedExport {
  std::size_t frames = 0;
  std::size_t vertices = 0;
  QuantizationCost quantization;  // zeros unless quantized
};

// Frames at f / fps seconds up to the end of the asset, plus the end itself when it falls between
// frames. kInvalidArgument when the frames would need 2 GiB or more; the writer's errors.
Result<BakedExport> writeBakedExport(const DeformAsset& asset, const DeformPlayer& player, const std::filesystem::path& path,
                                     double fps, const std::string& generator,
                                     const std::function<void(std::string_view, double)>& progress,
                                     const gltf::MaterialLibrary* materials = nullptr, bool quantize = false);

}  // namespace odeskin
