// SPDX-License-Identifier: MIT
#include "gltf_materials.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <string_view>
#include <tuple>
#include <utility>

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

// The encoded bytes hold a whole image of their type, as far as its framing shows: a PNG begins
// with its IHDR chunk and ends with IEND. (A renamed or cut file would otherwise travel into the
// output and fail there, in every viewer.)
bool wholeImage(const std::vector<unsigned char>& b, const std::string& mime_type) {
  if (mime_type != "image/png") return true;
  constexpr std::array<unsigned char, 8> kIhdr{0, 0, 0, 13, 'I', 'H', 'D', 'R'};
  constexpr std::array<unsigned char, 12> kIend{0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  return b.size() >= 8 + 25 + kIend.size() && std::equal(kIhdr.begin(), kIhdr.end(), b.begin() + 8) &&
         std::equal(kIend.begin(), kIend.end(), b.end() - static_cast<std::ptrdiff_t>(kIend.size()));
}

// The texture references of a material's core fields, by name, for checks and for stripping.
std::array<std::pair<const char*, int*>, 5> textureIndices(tinygltf::Material& m) {
  return {{{"baseColorTexture", &m.pbrMetallicRoughness.baseColorTexture.index},
           {"metallicRoughnessTexture", &m.pbrMetallicRoughness.metallicRoughnessTexture.index},
           {"normalTexture", &m.normalTexture.index},
           {"occlusionTexture", &m.occlusionTexture.index},
           {"emissiveTexture", &m.emissiveTexture.index}}};
}

// Whether an extension's JSON names a texture (a key such as "clearcoatTexture").
bool namesTexture(const tinygltf::Value& v) {
  if (v.IsObject()) {
    for (const std::string& key : v.Keys()) {
      if (key.ends_with("Texture") || namesTexture(v.Get(key))) return true;
    }
  } else if (v.IsArray()) {
    for (std::size_t i = 0; i < v.ArrayLen(); ++i) {
      if (namesTexture(v.Get(static_cast<int>(i)))) return true;
    }
  }
  return false;
}

Status checkReferences(MaterialLibrary& library) {
  const auto count = [](std::size_t n) { return static_cast<int>(n); };
  for (std::size_t i = 0; i < library.materials.size(); ++i) {
    tinygltf::Material& m = library.materials[i];
    for (const auto& [field, index] : textureIndices(m)) {
      if (*index < -1 || *index >= count(library.textures.size())) {
        return parseError(library.source + ": material " + std::to_string(i) + " '" + m.name + "': " + field +
                          " names texture " + std::to_string(*index) + ", and the file has " +
                          std::to_string(library.textures.size()));
      }
    }
  }
  for (std::size_t i = 0; i < library.textures.size(); ++i) {
    const tinygltf::Texture& t = library.textures[i];
    for (const auto& [what, index, have] : {std::tuple{"image", t.source, library.images.size()},
                                            std::tuple{"sampler", t.sampler, library.samplers.size()}}) {
      if (index < -1 || index >= count(have)) {
        return parseError(library.source + ": texture " + std::to_string(i) + " names " + what + " " + std::to_string(index) +
                          ", and the file has " + std::to_string(have));
      }
    }
  }
  return okStatus();
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
    if (!wholeImage(out.bytes, sniffed)) return parseError(what + " is not a whole " + sniffed.substr(6) + " file");
  }
  ODESKIN_TRY(checkReferences(library));
  return library;
}

std::size_t dropTextures(MaterialLibrary& library) {
  std::size_t dropped = 0;
  for (tinygltf::Material& m : library.materials) {
    bool textured = false;
    for (const auto& [field, index] : textureIndices(m)) {
      textured = textured || *index >= 0;
      *index = -1;
    }
    for (auto it = m.extensions.begin(); it != m.extensions.end();) {
      const bool drop = namesTexture(it->second);
      textured = textured || drop;
      it = drop ? m.extensions.erase(it) : std::next(it);
    }
    dropped += textured ? 1 : 0;
  }
  library.textures.clear();
  library.samplers.clear();
  library.images.clear();
  // Extensions of textures (KHR_texture_transform, ...) and of the material extensions just dropped.
  const auto unused = [&](const std::string& name) {
    if (!name.starts_with("KHR_materials_")) return true;
    return std::none_of(library.materials.begin(), library.materials.end(),
                        [&](const tinygltf::Material& m) { return m.extensions.count(name) > 0; });
  };
  for (std::vector<std::string>* list : {&library.extensions_used, &library.extensions_required}) {
    list->erase(std::remove_if(list->begin(), list->end(), unused), list->end());
  }
  return dropped;
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
