// SPDX-License-Identifier: MIT
// How the compact export's animation keys are interpolated. CUBICSPLINE carries the analytic
// tangents and needs few keys, but some importers drop the tangents (Blender 3.4 gives every
// imported CUBICSPLINE key automatic Bezier handles, glTF-Blender-IO#419) and then miss the motion
// between keys; LINEAR needs more keys and every importer plays it as written.
#pragma once

#include <optional>
#include <string_view>

namespace odeskin {

enum class KeyInterpolation { kCubicSpline, kLinear };

// The glTF sampler's interpolation name.
constexpr std::string_view gltfInterpolationName(KeyInterpolation k) {
  return k == KeyInterpolation::kLinear ? "LINEAR" : "CUBICSPLINE";
}

// "cubic" or "linear" (the command line's words); nullopt for anything else.
constexpr std::optional<KeyInterpolation> parseKeyInterpolation(std::string_view word) {
  if (word == "cubic") return KeyInterpolation::kCubicSpline;
  if (word == "linear") return KeyInterpolation::kLinear;
  return std::nullopt;
}

}  // namespace odeskin
