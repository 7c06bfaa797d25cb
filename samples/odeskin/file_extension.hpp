// SPDX-License-Identifier: MIT
// How every verb tells file formats apart: by the extension, case-insensitively (".OBJ" is ".obj").
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace odeskin {

// The extension with its dot, in lower case ("" when there is none).
inline std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// A glTF 2.0 file by its extension: .gltf (JSON) or .glb (binary).
inline bool isGltfFile(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".gltf" || ext == ".glb";
}

}  // namespace odeskin
