// SPDX-License-Identifier: MIT
// The runs of faces that a glTF input's primitives cover (RenderPrimitive, types.hpp): what the
// asset check, both glTF writers and the runtime's draw ranges all walk.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "types.hpp"

namespace odeskin {

// `primitives`, or, when the input recorded none, one run of all `face_count` faces without a
// material.
inline std::vector<RenderPrimitive> primitiveRuns(std::span<const RenderPrimitive> primitives, std::size_t face_count) {
  if (!primitives.empty()) return {primitives.begin(), primitives.end()};
  return {RenderPrimitive{static_cast<std::uint32_t>(face_count), -1}};
}

// Empty when the runs follow each other, name material -1 or a real one, and end at `face_count`
// (or there are none); else what is wrong, for a message.
inline std::string primitiveRunProblem(std::span<const RenderPrimitive> primitives, std::size_t face_count) {
  std::uint32_t previous_end = 0;
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    if (primitives[p].face_end < previous_end || primitives[p].material < -1) {
      return "render primitive " + std::to_string(p) + " ends at face " + std::to_string(primitives[p].face_end) +
             " with material " + std::to_string(primitives[p].material);
    }
    previous_end = primitives[p].face_end;
  }
  if (!primitives.empty() && previous_end != face_count) {
    return "the render primitives end at face " + std::to_string(previous_end) + " of " + std::to_string(face_count);
  }
  return {};
}

}  // namespace odeskin
