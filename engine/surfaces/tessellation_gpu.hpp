// SPDX-License-Identifier: MIT
// What the compute shader shaders/ode6_tessellate.comp reads, packed from a network on the host:
// the cardinal sets (branch, parameters and block matrices of each Ode6Cardinal, as float), the
// cardinal set of each patch, and the boundary samples of S, S_u, S_uu along the grid's v (the
// curves are splines evaluated here in double; the shader evaluates the cardinal functions and
// forms the weighted sums, as the CPU reference tessellation does).
#pragma once

#include <cstddef>
#include <vector>

#include "../core/gpu_layout.h"
#include "../core/result.hpp"
#include "network.hpp"
#include "tessellation.hpp"
#include "tessellation_layout.h"

namespace odeskin {

static_assert(sizeof(gpu::Ode6GpuCardinal) == 104);
static_assert(offsetof(gpu::Ode6GpuCardinal, even) == 32 && offsetof(gpu::Ode6GpuCardinal, odd) == 68);
static_assert(sizeof(gpu::TessellatePushConstants) == 48);

struct TessellationGpuData {
  TessellationGrid grid;
  std::vector<gpu::Ode6GpuCardinal> cardinals;  // network.cardinalCount()
  std::vector<std::uint32_t> patch_cardinals;   // rows x columns
  std::vector<gpu::Float4> boundary_samples;    // boundaries x 3 x grid columns
  gpu::TessellatePushConstants push{};          // first_item and item_count left 0

  std::size_t tableFloats() const { return cardinals.size() * grid.u_samples * 6; }
};

// Errors of tessellationGrid.
Result<TessellationGpuData> packTessellation(const Network& network, TessellationResolution resolution);

gpu::Ode6GpuCardinal packCardinal(const Ode6Cardinal& cardinal);

}  // namespace odeskin
