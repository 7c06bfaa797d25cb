// SPDX-License-Identifier: MIT
// `--material` and `--materials PARTS.json` of `odeskin fit`: the material of every part, with
// per-part overrides keyed by bone name or index (PipelineOptions::material / part_materials).
//   --material skin | static | rho,eta,zeta,xi
//   PARTS.json: {"default": "skin", "parts": {"<bone name or index>": "static" | "rho,eta,zeta,xi" |
//                {"rho": .., "eta": .., "zeta": .., "xi": .., "bending": "thesis" | "stiffening"}}}
// ("default" and "parts" are optional; "bending" is optional and defaults to "thesis").
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "engine/core/result.hpp"
#include "engine/offline/material.hpp"

namespace odeskin {

// skinMaterial(), staticMaterial(), or four finite comma-separated numbers rho,eta,zeta,xi.
// kInvalidArgument naming the text otherwise.
Result<Material> parseMaterial(std::string_view text);

struct MaterialChoice {
  Material default_material = skinMaterial();
  std::map<std::string, Material> parts;  // bone name or index as text -> material
};

// kParseError naming `source` for malformed JSON; kInvalidArgument naming `source` and the key for
// an unknown key, a wrong type, a non-finite number, an empty part name or a bad material text.
// `fallback` is the default material when the file has no "default".
Result<MaterialChoice> parseMaterialsJson(const std::string& text, const std::string& source,
                                          const Material& fallback = skinMaterial());
// Reads the file (kIoError naming the path), then parseMaterialsJson.
Result<MaterialChoice> readMaterialsJson(const std::filesystem::path& path, const Material& fallback = skinMaterial());

}  // namespace odeskin
