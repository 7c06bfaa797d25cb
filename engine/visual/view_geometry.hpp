// SPDX-License-Identifier: MIT
// World-space meshes and curves turned into the view-space float records the renderer uploads
// (render_shading.hpp). The camera's view transform is applied here in double precision, so the
// shaders only project; their input is what a test can recompute exactly.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "../core/types.hpp"
#include "render_shading.hpp"

namespace odeskin::visual {

// Vertex i: position view p_i, normal R n_i (R the rotation part of `view`, which is rigid up to a
// uniform scale; R leaves the scale out), value values[i] (0 when `values` is empty).
// Precondition: normals and a non-empty `values` have positions.size() entries.
std::vector<SurfaceVertex> surfaceVertices(const glm::dmat4& view, std::span<const Vec3> positions,
                                           std::span<const Vec3> normals, std::span<const double> values = {});

// view p for each point, as floats.
std::vector<glm::vec3> viewPoints(const glm::dmat4& view, std::span<const Vec3> points);

}  // namespace odeskin::visual
