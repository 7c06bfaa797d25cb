// SPDX-License-Identifier: MIT
// Internal to rig/: per-vertex sparse weight rows while weights are built (smoothing over the mesh,
// pruning to a few influences), and the face-list check shared by the weight builders.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "../core/status.hpp"
#include "../kernels/influences.hpp"
#include "../mesh/adjacency.hpp"

namespace odeskin {

struct BoneWeight {
  std::uint32_t bone = 0;
  double weight = 0.0;
};
using WeightRow = std::vector<BoneWeight>;  // sorted by bone, no repeats

// kInvalidArgument prefixed with `who`: malformed offsets, a face with fewer than 3 corners, or a
// vertex index >= vertex_count.
Status checkFaces(const FaceList& faces, std::size_t vertex_count, const std::string& who);

// `iterations` explicit steps of umbrella (uniform Laplacian) smoothing,
//   w_i <- (1 - lambda) w_i + lambda mean_{j in N(i)} w_j,
// which keeps rows that sum to 1 summing to 1 and non-negative rows non-negative.
void smoothRows(std::vector<WeightRow>& rows, const VertexAdjacency& adjacency, int iterations, double lambda);

// The `max_influences` largest weights of each row (ties: lower bone first), renormalised to sum
// to 1. Rows must have a positive entry.
Influences pruneRows(const std::vector<WeightRow>& rows, int max_influences);

}  // namespace odeskin
