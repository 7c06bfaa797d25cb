// SPDX-License-Identifier: MIT
#include "curve_lines.hpp"

#include <array>
#include <string>

namespace odeskin::visual {

Result<CurveSegments> curveSegments(std::span<const IsoCurve> curves, std::span<const Vec3> positions) {
  CurveSegments out;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const std::vector<CurvePoint>& points = curves[c].points;
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (points[k].a >= positions.size() || points[k].b >= positions.size()) {
        return invalidArgument("curve " + std::to_string(c) + " point " + std::to_string(k) + " uses vertex " +
                               std::to_string(std::max(points[k].a, points[k].b)) + " of " +
                               std::to_string(positions.size()));
      }
    }
    const std::size_t segments = points.size() < 2 ? 0 : (curves[c].closed ? points.size() : points.size() - 1);
    for (std::size_t k = 0; k < segments; ++k) {
      out.endpoints.push_back(curvePointPosition(positions, points[k]));
      out.endpoints.push_back(curvePointPosition(positions, points[(k + 1) % points.size()]));
      out.curve_of_segment.push_back(static_cast<std::uint32_t>(c));
      out.part_of_segment.push_back(curves[c].part);
    }
  }
  return out;
}

glm::vec3 curveColour(std::uint32_t index) {
  // Saturated and mid-dark, so every one stands out from the clay grey surface.
  static constexpr std::array<glm::vec3, 6> kPalette{
      glm::vec3(0.80f, 0.12f, 0.10f), glm::vec3(0.10f, 0.35f, 0.80f), glm::vec3(0.05f, 0.55f, 0.25f),
      glm::vec3(0.75f, 0.40f, 0.00f), glm::vec3(0.50f, 0.15f, 0.65f), glm::vec3(0.00f, 0.50f, 0.55f)};
  return kPalette[index % kPalette.size()];
}

}  // namespace odeskin::visual
