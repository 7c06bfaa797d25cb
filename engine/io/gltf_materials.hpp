// SPDX-License-Identifier: MIT
// The look of a glTF file (its materials with the textures, samplers and images they use) read
// to dress a mesh odeskin writes: `export --materials` and `play --materials` give a fitted
// character back the materials of the file it was fitted from. Images travel as their encoded
// bytes (PNG, JPEG, KTX2, WebP, AVIF), never decoded.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin::gltf {

struct EncodedImage {
  std::string name;
  std::string mime_type;  // "image/png", "image/jpeg", "image/ktx2", "image/webp" or "image/avif"
  std::vector<unsigned char> bytes;
};

struct MaterialLibrary {
  std::string source;  // the file, for messages
  std::vector<tinygltf::Material> materials;
  std::vector<tinygltf::Texture> textures;
  std::vector<tinygltf::Sampler> samplers;
  std::vector<EncodedImage> images;
  std::vector<std::string> extensions_used;      // the source's extensions these use
  std::vector<std::string> extensions_required;  // those of them the source requires
};

// Every material, texture, sampler and image of `path`, indices unchanged. kIoError or
// kParseError naming the file (loadModelWithImages), an image whose bytes cannot be had (an
// external file missing), whose type is none of those above or whose PNG framing is cut, or a
// material or texture naming a texture, image or sampler the file lacks; kInvalidArgument for a
// file with no materials.
Result<MaterialLibrary> readMaterialLibrary(const std::filesystem::path& path);

// For a mesh without TEXCOORD_0, where no texture can be mapped (glTF then refuses the file):
// every texture reference goes (the core fields, and material extensions that name a texture),
// with the textures, samplers and images; factors stay. Returns how many materials had textures.
std::size_t dropTextures(MaterialLibrary& library);

// The material of each primitive of a mesh odeskin writes: the input's own (RenderPrimitive), or,
// for an asset that recorded none, the library's only material. kInvalidArgument naming the
// library's file when a primitive's material is not in it, or when the asset recorded none and the
// library has several.
Result<std::vector<int>> primitiveMaterials(const MaterialLibrary& library, std::span<const RenderPrimitive> primitives,
                                            std::size_t primitive_count);

// One primitive a writer emits: its index accessor and its material (-1: none).
struct PrimitiveIndices {
  int indices = -1;
  int material = -1;
};

// The runs of `faces` (primitiveRuns of `primitives`) as index accessors over one shared set of
// vertices, each with its primitive's material from `materials` (primitiveMaterials), or none when
// it is null. Runs without faces are left out. Errors: primitiveMaterials'.
Result<std::vector<PrimitiveIndices>> appendPrimitiveIndices(tinygltf::Model& model, const FaceList& faces,
                                                             std::span<const RenderPrimitive> primitives,
                                                             const MaterialLibrary* materials);

// `mesh` gets one primitive per entry of `primitives`: `shared` (the vertex attributes and morph
// targets they all use) with that entry's indices and material.
void addSharedPrimitives(tinygltf::Mesh& mesh, const tinygltf::Primitive& shared, std::span<const PrimitiveIndices> primitives);

// Appends the library to `model`: materials, textures and samplers as they were, each image as a
// bufferView of buffer 0 with its mime type, and the extensions they use.
void addMaterialLibrary(tinygltf::Model& model, const MaterialLibrary& library);

}  // namespace odeskin::gltf
