// SPDX-License-Identifier: MIT
// Internal to rig/: a bone's vertices should form one connected region of the mesh. After each
// assignment, every cluster keeps only its largest connected piece; the vertices of its other
// pieces flood into adjacent kept pieces wave by wave, each taking the adjacent cluster that fits
// it best, so the result is connected by construction.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "../mesh/adjacency.hpp"

namespace odeskin {

// cost(cluster, vertex, stop_above): the vertex's fit error in that cluster (may stop early once
// above stop_above).
using ClusterCost = std::function<double(std::uint32_t, std::uint32_t, double)>;

// `labels`: V cluster indices < clusters. A mesh component that holds no cluster's largest piece
// keeps its labels (its clusters then span several components).
void keepClustersConnected(const VertexAdjacency& adjacency, std::size_t clusters, std::vector<std::uint32_t>& labels,
                           const ClusterCost& cost);

}  // namespace odeskin
