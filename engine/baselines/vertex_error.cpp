// SPDX-License-Identifier: MIT
#include "vertex_error.hpp"

#include <string>

#include "../core/finite_vector.hpp"
#include "../offline/residual_fit.hpp"

namespace odeskin {

Result<VertexError> vertexError(std::span<const Vec3> deformed, std::span<const Vec3> truth) {
  if (deformed.size() != truth.size()) {
    return invalidArgument("vertex error: " + std::to_string(deformed.size()) + " deformed vertices against " +
                           std::to_string(truth.size()) + " ground-truth vertices");
  }
  if (truth.empty()) return invalidArgument("vertex error: the meshes have no vertices");
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!isFinite(truth[i])) return invalidArgument("vertex error: ground-truth vertex " + std::to_string(i) + " is not finite");
    if (!isFinite(deformed[i])) return invalidArgument("vertex error: deformed vertex " + std::to_string(i) + " is not finite");
  }
  VertexError out;
  out.box_side = longestBoxSide(truth);
  if (!(out.box_side > 0.0)) return degenerate("vertex error: the ground truth's bounding box has no extent (Lbox = 0)");
  double worst = -1.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double d = glm::length(deformed[i] - truth[i]);
    sum += d;
    if (d > worst) {
      worst = d;
      out.worst_vertex = i;
    }
  }
  out.mve = worst / out.box_side;
  out.mean = sum / static_cast<double>(truth.size()) / out.box_side;
  return out;
}

}  // namespace odeskin
