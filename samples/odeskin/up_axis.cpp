// SPDX-License-Identifier: MIT
#include "up_axis.hpp"

#include <string>

namespace odeskin {

Result<Vec3> parseUpAxis(std::string_view text) {
  const bool negative = !text.empty() && text.front() == '-';
  const std::string_view axis = negative ? text.substr(1) : text;
  Vec3 up(0.0);
  if (axis == "x") {
    up.x = 1.0;
  } else if (axis == "y") {
    up.y = 1.0;
  } else if (axis == "z") {
    up.z = 1.0;
  } else {
    return invalidArgument("--up '" + std::string(text) + "' must be x, y, z, -x, -y or -z");
  }
  return negative ? -up : up;
}

Result<Vec3> curveRigUp(std::string_view rig, std::string_view up) {
  if (up.empty()) return Vec3(0.0, 1.0, 0.0);
  if (rig != "curves") return invalidArgument("--up applies to --rig curves (its skeleton templates' up axis)");
  return parseUpAxis(up);
}

}  // namespace odeskin
