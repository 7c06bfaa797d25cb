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

namespace {

// Tableau's ten categorical colours without its grey (which would vanish on the clay surface),
// slightly darkened so thin lines stay visible on a light surface.
constexpr std::array<glm::vec3, 9> kPalette{
    glm::vec3(0.12f, 0.42f, 0.68f), glm::vec3(0.92f, 0.45f, 0.04f), glm::vec3(0.15f, 0.56f, 0.15f),
    glm::vec3(0.80f, 0.14f, 0.15f), glm::vec3(0.52f, 0.36f, 0.70f), glm::vec3(0.50f, 0.30f, 0.26f),
    glm::vec3(0.86f, 0.40f, 0.70f), glm::vec3(0.62f, 0.62f, 0.08f), glm::vec3(0.05f, 0.64f, 0.72f)};

}  // namespace

std::uint32_t curvePaletteSize() { return static_cast<std::uint32_t>(kPalette.size()); }

glm::vec3 curveColour(std::uint32_t index) { return kPalette[index % kPalette.size()]; }

}  // namespace odeskin::visual
