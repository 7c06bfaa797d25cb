// SPDX-License-Identifier: MIT
#include "tessellation_gpu.hpp"

namespace odeskin {

static_assert(ODESKIN_ODE6_SERIES_TERMS == kOde6SeriesTerms);
static_assert(ODESKIN_ODE6_SERIES == static_cast<std::uint32_t>(Ode6Branch::kSeries) &&
              ODESKIN_ODE6_REAL == static_cast<std::uint32_t>(Ode6Branch::kReal) &&
              ODESKIN_ODE6_PQ == static_cast<std::uint32_t>(Ode6Branch::kPq));

gpu::Ode6GpuCardinal packCardinal(const Ode6Cardinal& cardinal) {
  const Ode6Basis& b = cardinal.basis();
  gpu::Ode6GpuCardinal g{};
  g.branch = static_cast<std::uint32_t>(b.branch);
  g.b = static_cast<float>(b.b);
  g.c = static_cast<float>(b.c);
  g.x1 = static_cast<float>(b.x1);
  g.x2 = static_cast<float>(b.x2);
  g.w = static_cast<float>(b.w);
  for (std::size_t l = 0; l < 3; ++l) {
    for (std::size_t i = 0; i < 3; ++i) {
      g.even[3 * l + i] = static_cast<float>(b.even[l][i]);
      g.odd[3 * l + i] = static_cast<float>(b.odd[l][i]);
    }
  }
  return g;
}

Result<TessellationGpuData> packTessellation(const Network& network, TessellationResolution resolution) {
  TessellationGpuData d;
  ODESKIN_ASSIGN_OR_RETURN(d.grid, tessellationGrid(network, resolution));
  for (std::uint32_t k = 0; k < network.cardinalCount(); ++k) d.cardinals.push_back(packCardinal(network.cardinalAt(k)));
  for (std::uint32_t p = 0; p < network.patchCount(); ++p) {
    d.patch_cardinals.push_back(network.cardinalIndex(p / network.columns(), p % network.columns()));
  }
  const std::uint32_t width = d.grid.gridColumns();
  const auto boundaries = static_cast<std::uint32_t>(network.description().boundaries.size());
  d.boundary_samples.resize(std::size_t{boundaries} * 3 * width);
  for (std::uint32_t b = 0; b < boundaries; ++b) {
    const std::vector<BoundarySample> samples = sampleBoundary(network, b, d.grid);
    for (std::uint32_t j = 0; j < width; ++j) {
      const Vec3 k[3] = {samples[j].position, samples[j].first, samples[j].second};
      for (std::size_t i = 0; i < 3; ++i) {
        d.boundary_samples[(3 * std::size_t{b} + i) * width + j] = {static_cast<float>(k[i].x), static_cast<float>(k[i].y),
                                                                     static_cast<float>(k[i].z), 0.0f};
      }
    }
  }
  d.push.rows = d.grid.rows;
  d.push.columns = d.grid.columns;
  d.push.u_samples = d.grid.u_samples;
  d.push.v_samples = d.grid.v_samples;
  d.push.grid_columns = width;
  d.push.boundary_count = boundaries;
  return d;
}

}  // namespace odeskin
