// SPDX-License-Identifier: MIT
// Loading a .gltf or .glb file through tinygltf (internal to odeskin_gltf), and the
// extensionsRequired check tinygltf leaves to its caller.
#pragma once

#include <filesystem>
#include <string>

#include <tiny_gltf.h>

#include "../core/result.hpp"

namespace odeskin::gltf {

// GLB or JSON glTF by the file's first four bytes ("glTF" is GLB), whatever its extension. Images
// are not decoded (odeskin reads geometry only; this also keeps KTX2/WebP images from failing the
// load). kIoError naming the path: missing, unreadable, or over 2 GiB (tinygltf 2.7 has no size
// guard). kParseError naming the path with tinygltf's message when it refuses the file, or for a
// GLB whose second (BIN) chunk runs past the file's end, which tinygltf 2.7 would read past, a GLB
// with two buffers without a uri, each of which tinygltf 2.7 would fill with a copy of that chunk,
// or an image whose bufferView lies outside its buffer, which tinygltf 2.7 would point past; an
// external file that is not a regular file, or is over 2 GiB, is not read (tinygltf's message).
// EXT_meshopt_compression bufferViews come back decoded, with decodeMeshoptViews' errors
// (gltf_meshopt.hpp); its placeholder and fallback buffers are not read.
Result<tinygltf::Model> loadModel(const std::filesystem::path& path);

// loadModel keeping every image it can read as its encoded bytes (Image::image, as_is), not
// decoded: to copy a file's textures into another (gltf_materials.hpp). An image whose external
// file is missing keeps only its uri.
Result<tinygltf::Model> loadModelWithImages(const std::filesystem::path& path);

// loadModel on bytes already in memory; `source` stands for the path in the messages. It has no
// folder: a buffer URI other than a data: URI is refused (tinygltf's message), and no file is
// touched. kIoError over 2 GiB.
Result<tinygltf::Model> loadModelFromMemory(const std::string& bytes, const std::string& source);

// kInvalidArgument naming the first extensionsRequired entry odeskin does not handle. Handled:
// KHR_mesh_quantization and EXT_meshopt_compression (decoded), and extensions confined to materials, textures and lights
// (KHR_materials_*, KHR_texture_transform, KHR_texture_basisu, EXT_texture_webp, EXT_texture_avif,
// KHR_lights_punctual), which cannot change geometry, skins, morph targets or animation.
Status checkRequiredExtensions(const tinygltf::Model& model);

// Whether the file declares KHR_mesh_quantization (used or required).
bool usesMeshQuantization(const tinygltf::Model& model);

}  // namespace odeskin::gltf
