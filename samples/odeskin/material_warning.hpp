// SPDX-License-Identifier: MIT
// The warning of export, play and rig when a glTF's materials dress a mesh that has no texture
// coordinates: their textures cannot be mapped, so they are left out (gltf::dropTextures).
#pragma once

#include <cstddef>
#include <filesystem>
#include <ostream>

namespace odeskin {

inline void warnOfDroppedTextures(std::ostream& err, const std::filesystem::path& mesh, const std::filesystem::path& materials,
                                  std::size_t untextured) {
  if (untextured == 0) return;
  err << "warning: " << mesh.string() << " has no texture coordinates, so the textures of " << untextured << " material"
      << (untextured == 1 ? "" : "s") << " from " << materials.string()
      << " are left out (their colours and factors are kept)\n";
}

}  // namespace odeskin
