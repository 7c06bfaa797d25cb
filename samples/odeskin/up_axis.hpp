// SPDX-License-Identifier: MIT
// The --up option of render, rig, surface, and fit/evaluate with --rig curves.
#pragma once

#include <string_view>

#include "engine/core/result.hpp"
#include "engine/core/types.hpp"

namespace odeskin {

// "x", "y", "z", "-x", "-y", "-z" as a unit vector. kInvalidArgument quoting the text.
Result<Vec3> parseUpAxis(std::string_view text);

}  // namespace odeskin
