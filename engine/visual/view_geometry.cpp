// SPDX-License-Identifier: MIT
#include "view_geometry.hpp"

#include <glm/geometric.hpp>

namespace odeskin::visual {

std::vector<SurfaceVertex> surfaceVertices(const glm::dmat4& view, std::span<const Vec3> positions,
                                           std::span<const Vec3> normals, std::span<const double> values) {
  // The view may carry a uniform scale (the renderer's, to fit float's range): normals lose it.
  const glm::dmat3 linear(view);
  const glm::dmat3 rotation = linear / glm::length(linear[0]);
  std::vector<SurfaceVertex> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3 p(view * glm::dvec4(positions[i], 1.0));
    const glm::vec3 n(rotation * normals[i]);
    out[i] = {{p.x, p.y, p.z}, {n.x, n.y, n.z}, values.empty() ? 0.0f : static_cast<float>(values[i])};
  }
  return out;
}

std::vector<glm::vec3> viewPoints(const glm::dmat4& view, std::span<const Vec3> points) {
  std::vector<glm::vec3> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.emplace_back(view * glm::dvec4(p, 1.0));
  return out;
}

}  // namespace odeskin::visual
