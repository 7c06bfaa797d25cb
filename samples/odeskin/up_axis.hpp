// SPDX-License-Identifier: MIT
// The --up option of render, rig, surface, and fit/evaluate with --rig curves.
#pragma once

#include <string_view>

#include "engine/core/result.hpp"
#include "engine/core/types.hpp"

namespace odeskin {

// "x", "y", "z", "-x", "-y", "-z" as a unit vector. kInvalidArgument quoting the text.
Result<Vec3> parseUpAxis(std::string_view text);

// fit's and evaluate's --up, which only the curve rig's templates use: +y when `up` is empty, else
// parseUpAxis(up). kInvalidArgument when `up` is given with a `rig` other than "curves".
Result<Vec3> curveRigUp(std::string_view rig, std::string_view up);

}  // namespace odeskin
