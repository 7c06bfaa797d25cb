// SPDX-License-Identifier: MIT
#include "vertex_error.hpp"

#include <string>

#include "camera.hpp"

namespace odeskin::visual {

Result<std::vector<double>> relativeVertexErrors(std::span<const Vec3> positions, std::span<const Vec3> reference) {
  if (positions.size() != reference.size()) {
    return invalidArgument(std::to_string(positions.size()) + " vertices but the reference has " +
                           std::to_string(reference.size()));
  }
  const double diagonal = boundsOf(reference).diagonal();
  if (!(diagonal > 0.0)) return invalidArgument("the reference mesh has no extent (zero bounding box)");
  std::vector<double> errors(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) errors[i] = glm::length(positions[i] - reference[i]) / diagonal;
  return errors;
}

}  // namespace odeskin::visual
