// SPDX-License-Identifier: MIT
#include "gltf_materials.hpp"

#include <algorithm>
#include <array>
#include <string_view>

#include "../core/render_primitives.hpp"
#include "gltf_buffer_builder.hpp"
#include "gltf_load.hpp"

namespace odeskin::gltf {
namespace {

// Extensions that live on materials, textures and images only, so they travel with them.
bool isMaterialExtension(std::string_view name) {
  constexpr std::array<std::string_view, 4> kTextures{"KHR_texture_transform", "KHR_texture_basisu", "EXT_texture_webp",
                                                      "EXT_texture_avif"};
  return name.starts_with("KHR_materials_") || std::find(kTextures.begin(), kTextures.end(), name) != kTextures.end();
}

// The mime type of encoded image bytes by their signature; empty when none is known.
std::string sniffMimeType(const std::vector<unsigned char>& b) {
  auto starts = [&](std::initializer_list<unsigned char> magic, std::size_t at = 0) {
    return b.size() >= at + magic.size() && std::equal(magic.begin(), magic.end(), b.begin() + static_cast<std::ptrdiff_t>(at));
  };
  if (starts({0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'})) return "image/png";
  if (starts({0xFF, 0xD8, 0xFF})) return "image/jpeg";
  if (starts({0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB})) return "image/ktx2";
  if (starts({'R', 'I', 'F', 'F'}) && starts({'W', 'E', 'B', 'P'}, 8)) return "image/webp";
  if (starts({'f', 't', 'y', 'p', 'a', 'v', 'i', 'f'}, 4)) return "image/avif";
  return {};
}

std::vector<std::string> materialExtensions(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  std::copy_if(names.begin(), names.end(), std::back_inserter(out), [](const std::string& n) { return isMaterialExtension(n); });
  return out;
}

}  // namespace

Result<MaterialLibrary> readMaterialLibrary(const std::filesystem::path& path) {
  ODESKIN_ASSIGN_OR_RETURN(tinygltf::Model model, loadModelWithImages(path));
  MaterialLibrary library;
  library.source = path.string();
  if (model.materials.empty()) return invalidArgument(library.source + ": has no materials to copy");
  library.materials = std::move(model.materials);
  library.textures = std::move(model.textures);
  library.samplers = std::move(model.samplers);
  library.extensions_used = materialExtensions(model.extensionsUsed);
  library.extensions_required = materialExtensions(model.extensionsRequired);
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& image = model.images[i];
    EncodedImage& out = library.images.emplace_back();
    out.name = image.name;
    out.bytes = std::move(image.image);
    const std::string what = library.source + ": image " + std::to_string(i) + (image.uri.empty() ? "" : " (" + image.uri + ")");
    if (out.bytes.empty()) return parseError(what + " cannot be read");
    const std::string sniffed = sniffMimeType(out.bytes);
    out.mime_type = image.mimeType.empty() ? sniffed : image.mimeType;
    if (out.mime_type.empty() || sniffed.empty()) {
      return parseError(what + " is not PNG, JPEG, KTX2, WebP or AVIF");
    }
  }
  return library;
}

Result<std::vector<int>> primitiveMaterials(const MaterialLibrary& library, std::span<const RenderPrimitive> primitives,
                                            std::size_t primitive_count) {
  const std::size_t count = library.materials.size();
  if (primitives.empty()) {
    if (count == 1) return std::vector<int>(primitive_count, 0);
    return invalidArgument(library.source + ": has " + std::to_string(count) +
                           " materials, and the asset does not record which its primitives used (fit it again from "
                           "its glTF file); a file with one material dresses any asset");
  }
  std::vector<int> out;
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    const std::int32_t m = primitives[p].material;
    if (m >= 0 && static_cast<std::size_t>(m) >= count) {
      return invalidArgument(library.source + ": has " + std::to_string(count) + " materials, but the asset's primitive " +
                             std::to_string(p) + " used material " + std::to_string(m) +
                             " (is it the file the asset was fitted from?)");
    }
    out.push_back(m);
  }
  return out;
}

Result<std::vector<PrimitiveIndices>> appendPrimitiveIndices(tinygltf::Model& model, const FaceList& faces,
                                                             std::span<const RenderPrimitive> primitives,
                                                             const MaterialLibrary* materials) {
  const std::vector<RenderPrimitive> runs = primitiveRuns(primitives, faces.faceCount());
  std::vector<int> chosen(runs.size(), -1);
  if (materials != nullptr) {
    ODESKIN_ASSIGN_OR_RETURN(chosen, primitiveMaterials(*materials, primitives, runs.size()));
  }
  std::vector<PrimitiveIndices> out;
  std::uint32_t begin = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (runs[r].face_end > begin) {
      out.push_back({appendTriangleIndices(model, fanTriangles(faces, begin, runs[r].face_end)), chosen[r]});
    }
    begin = runs[r].face_end;
  }
  return out;
}

void addSharedPrimitives(tinygltf::Mesh& mesh, const tinygltf::Primitive& shared, std::span<const PrimitiveIndices> primitives) {
  for (const PrimitiveIndices& p : primitives) {
    mesh.primitives.push_back(shared);
    mesh.primitives.back().indices = p.indices;
    mesh.primitives.back().material = p.material;
  }
}

void addMaterialLibrary(tinygltf::Model& model, const MaterialLibrary& library) {
  model.materials.insert(model.materials.end(), library.materials.begin(), library.materials.end());
  model.textures.insert(model.textures.end(), library.textures.begin(), library.textures.end());
  model.samplers.insert(model.samplers.end(), library.samplers.begin(), library.samplers.end());
  for (const EncodedImage& encoded : library.images) {
    tinygltf::Image image;
    image.name = encoded.name;
    image.mimeType = encoded.mime_type;
    image.bufferView = appendView(model, encoded.bytes.data(), encoded.bytes.size(), 0);
    model.images.push_back(std::move(image));
  }
  auto addMissing = [](std::vector<std::string>& list, const std::vector<std::string>& names) {
    for (const std::string& name : names) {
      if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
    }
  };
  addMissing(model.extensionsUsed, library.extensions_used);
  addMissing(model.extensionsRequired, library.extensions_required);
}

}  // namespace odeskin::gltf
