// SPDX-License-Identifier: MIT
// Real meshes at any vertex count for the benchmark harness: vertex i of the tiled asset is vertex
// i mod V of the source, with all of its per-vertex data (binding, influences, residuals, remainder
// index), so every vertex costs exactly what a real one costs. Curves, coefficients, materials and
// bones are shared, as instances of one character share them. Faces and the display curves (whose
// points name source vertices) are dropped: the deformation kernels never read them.
#pragma once

#include <cstddef>

#include "engine/core/result.hpp"
#include "engine/offline/deform_asset.hpp"

namespace odeskin::bench {

// kInvalidArgument when `source` has no vertices or `vertex_count` is 0.
Result<DeformAsset> tileDeformAsset(const DeformAsset& source, std::size_t vertex_count);

}  // namespace odeskin::bench
