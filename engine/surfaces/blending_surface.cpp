// SPDX-License-Identifier: MIT
#include "blending_surface.hpp"

#include <cstdio>

#include "../core/finite_vector.hpp"

namespace odeskin {

Result<BlendingSurface> BlendingSurface::create(BoundaryData boundary, double alpha, double beta, double gamma) {
  ODESKIN_ASSIGN_OR_RETURN(Ode4Cardinal cardinal, Ode4Cardinal::create(alpha, beta, gamma));
  return BlendingSurface(std::move(boundary), [cardinal](double u) { return cardinal.at(u); });
}

Result<BlendingSurface> BlendingSurface::create(BoundaryData boundary, CardinalFunction cardinals) {
  if (!cardinals) return invalidArgument("blending surface: the cardinal functions are empty");
  return BlendingSurface(std::move(boundary), std::move(cardinals));
}

Vec3 BlendingSurface::at(double u, double v) const { return combine(cardinals_(u).r, boundary_.at(v)); }

Vec3 BlendingSurface::derivativeU(double u, double v) const { return combine(cardinals_(u).dr, boundary_.at(v)); }

double blendGridV(const VDomain& domain, std::uint32_t v_count, std::uint32_t j) {
  const double span = domain.v_end - domain.v_begin;
  const double steps = domain.periodic ? static_cast<double>(v_count) : static_cast<double>(v_count - 1);
  return domain.v_begin + span * static_cast<double>(j) / steps;
}

Result<BlendGrid> tessellateBlend(const BlendingSurface& surface, std::uint32_t u_count, std::uint32_t v_count) {
  const VDomain& domain = surface.boundary().domain();
  const std::uint32_t min_v = domain.periodic ? 3 : 2;
  if (u_count < 2) return outOfRange("blend grid: " + std::to_string(u_count) + " samples in u, need at least 2");
  if (v_count < min_v) {
    return outOfRange("blend grid: " + std::to_string(v_count) + " samples in v, need at least " +
                      std::to_string(min_v) + (domain.periodic ? " (the grid wraps in v)" : ""));
  }
  const std::uint64_t total = std::uint64_t{u_count} * v_count;
  if (total > kMaxBlendGridVertices) {
    return outOfRange("blend grid: " + std::to_string(u_count) + " x " + std::to_string(v_count) +
                      " vertices exceed the limit of " + std::to_string(kMaxBlendGridVertices));
  }
  std::vector<TrimlineSample> columns(v_count);
  for (std::uint32_t j = 0; j < v_count; ++j) columns[j] = surface.boundary().at(blendGridV(domain, v_count, j));

  BlendGrid grid;
  grid.u_count = u_count;
  grid.v_count = v_count;
  grid.wraps_v = domain.periodic;
  grid.positions.resize(static_cast<std::size_t>(total));
  for (std::uint32_t i = 0; i < u_count; ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(u_count - 1);
    const std::array<double, 4> r = surface.cardinals()(u).r;
    for (std::uint32_t j = 0; j < v_count; ++j) {
      const Vec3 p = BlendingSurface::combine(r, columns[j]);
      if (!isFinite(p)) {
        char where[64];
        std::snprintf(where, sizeof where, "(u, v) = (%g, %g)", u, blendGridV(domain, v_count, j));
        return invalidArgument(std::string("blend grid: the surface is not finite at ") + where +
                               " (check the boundary data there)");
      }
      grid.positions[std::size_t{i} * v_count + j] = p;
    }
  }

  const std::uint32_t v_faces = domain.periodic ? v_count : v_count - 1;
  const std::size_t quads = std::size_t{u_count - 1} * v_faces;
  grid.faces.face_offsets.reserve(quads + 1);
  grid.faces.indices.reserve(4 * quads);
  for (std::uint32_t i = 0; i + 1 < u_count; ++i) {
    for (std::uint32_t j = 0; j < v_faces; ++j) {
      const std::uint32_t k = (j + 1) % v_count;
      grid.faces.indices.insert(grid.faces.indices.end(),
                                {i * v_count + j, (i + 1) * v_count + j, (i + 1) * v_count + k, i * v_count + k});
      grid.faces.face_offsets.push_back(static_cast<std::uint32_t>(grid.faces.indices.size()));
    }
  }
  return grid;
}

}  // namespace odeskin
