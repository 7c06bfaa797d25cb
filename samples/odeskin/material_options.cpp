// SPDX-License-Identifier: MIT
#include "material_options.hpp"

#include <cmath>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "engine/core/input_file.hpp"
#include "engine/core/json_path.hpp"
#include "engine/core/number_text.hpp"

namespace odeskin {
namespace {

using Json = nlohmann::json;

// Spaces around a field are allowed: "1, 2, 3, 4" reads as typed.
Result<double> finiteNumber(std::string_view text, const std::string& what) {
  const std::size_t first = text.find_first_not_of(" \t");
  const std::size_t last = text.find_last_not_of(" \t");
  const std::optional<double> x =
      first == std::string_view::npos ? std::nullopt : finiteNumberIn(text.substr(first, last + 1 - first));
  if (!x) return invalidArgument(what + ": '" + std::string(text) + "' is not a finite number");
  return *x;
}

Result<Material> materialFromObject(const Json& object, const std::string& where) {
  Material m;
  bool seen[4] = {false, false, false, false};
  static const char* const kNames[4] = {"rho", "eta", "zeta", "xi"};
  double* const fields[4] = {&m.rho, &m.eta, &m.zeta, &m.xi};
  for (const auto& [key, value] : object.items()) {
    if (key == "bending") {
      if (value == "thesis") {
        m.bending = BendingSign::kThesis;
      } else if (value == "stiffening") {
        m.bending = BendingSign::kStiffening;
      } else {
        return invalidArgument(where + ": \"bending\" must be \"thesis\" or \"stiffening\"");
      }
      continue;
    }
    int k = 0;
    while (k < 4 && key != kNames[k]) ++k;
    if (k == 4) return invalidArgument(where + ": unknown key \"" + key + "\" (expected rho, eta, zeta, xi, bending)");
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      return invalidArgument(where + ": \"" + key + "\" must be a finite number");
    }
    *fields[k] = value.get<double>();
    seen[k] = true;
  }
  for (int k = 0; k < 4; ++k) {
    if (!seen[k]) return invalidArgument(where + ": \"" + kNames[k] + "\" is missing");
  }
  return m;
}

Result<Material> materialFromJson(const Json& value, const std::string& where) {
  if (value.is_string()) {
    Result<Material> m = parseMaterial(value.get<std::string>());
    if (!m.ok()) return invalidArgument(where + ": " + m.status().message());
    return m;
  }
  if (value.is_object()) return materialFromObject(value, where);
  return invalidArgument(where + ": a material is \"skin\", \"static\", \"rho,eta,zeta,xi\" or an object with those keys");
}

}  // namespace

Result<Material> parseMaterial(std::string_view text) {
  if (text == "skin") return skinMaterial();
  if (text == "static") return staticMaterial();
  Material m;
  double* const fields[4] = {&m.rho, &m.eta, &m.zeta, &m.xi};
  std::size_t start = 0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t comma = text.find(',', start);
    if ((k < 3) != (comma != std::string_view::npos)) {
      return invalidArgument("material '" + std::string(text) + "': expected skin, static or rho,eta,zeta,xi");
    }
    const std::string_view field = text.substr(start, k < 3 ? comma - start : std::string_view::npos);
    ODESKIN_ASSIGN_OR_RETURN(*fields[k], finiteNumber(field, "material '" + std::string(text) + "'"));
    start = comma + 1;
  }
  return m;
}

Result<MaterialChoice> parseMaterialsJson(const std::string& text, const std::string& source, const Material& fallback) {
  const Json root = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded()) return parseError(source + ": not valid JSON");
  if (const std::string twice = duplicateJsonKey(text); !twice.empty()) return parseError(source + ": " + twice);
  if (!root.is_object()) return invalidArgument(source + ": expected an object with \"default\" and \"parts\"");
  MaterialChoice choice;
  choice.default_material = fallback;
  for (const auto& [key, value] : root.items()) {
    if (key == "default") {
      ODESKIN_ASSIGN_OR_RETURN(choice.default_material, materialFromJson(value, source + ": \"default\""));
    } else if (key == "parts") {
      if (!value.is_object()) return invalidArgument(source + ": \"parts\" must be an object of part: material");
      for (const auto& [part, material] : value.items()) {
        if (part.empty()) return invalidArgument(source + ": a part has an empty name");
        ODESKIN_ASSIGN_OR_RETURN(choice.parts[part], materialFromJson(material, source + ": part \"" + part + "\""));
      }
    } else {
      return invalidArgument(source + ": unknown key \"" + key + "\" (expected \"default\" and \"parts\")");
    }
  }
  return choice;
}

Result<MaterialChoice> readMaterialsJson(const std::filesystem::path& path, const Material& fallback) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string text, readInputFile(path));
  return parseMaterialsJson(text, path.string(), fallback);
}

}  // namespace odeskin
