// SPDX-License-Identifier: MIT
#include "engine/rig/cluster_connectivity.hpp"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

// Vertices 0 - 1 - ... - (n - 1) in a line, as compressed rows.
VertexAdjacency path(std::uint32_t n) {
  VertexAdjacency a;
  a.offsets = {0};
  for (std::uint32_t v = 0; v < n; ++v) {
    if (v > 0) a.neighbours.push_back(v - 1);
    if (v + 1 < n) a.neighbours.push_back(v + 1);
    a.offsets.push_back(static_cast<std::uint32_t>(a.neighbours.size()));
  }
  return a;
}

// Every cluster fits every vertex alike: the first adjacent cluster wins.
double flat(std::uint32_t /*cluster*/, std::uint32_t /*vertex*/, double /*stop_above*/) { return 0.0; }

TEST(KeepClustersConnected, StrayPiecesFloodInFromTheKeptOnesWaveByWave) {
  // Cluster 0: {0, 1, 2} kept, {5, 6} stray; cluster 1: {3, 4} kept, {7} stray. The stray run
  // 5-7 has one kept neighbour (4), so it turns to cluster 1 one vertex per wave.
  std::vector<std::uint32_t> labels = {0, 0, 0, 1, 1, 0, 0, 1};
  keepClustersConnected(path(8), 2, labels, flat);
  EXPECT_EQ(labels, (std::vector<std::uint32_t>{0, 0, 0, 1, 1, 1, 1, 1}));
}

TEST(KeepClustersConnected, AStrayVertexTakesTheAdjacentClusterThatFitsItBest) {
  // Vertex 1 is cluster 1's stray piece ({3, 4} is its largest); of its neighbours' clusters 0
  // and 2, cluster 2 fits it better.
  std::vector<std::uint32_t> labels = {0, 1, 2, 1, 1};
  std::vector<double> stops;
  keepClustersConnected(path(5), 3, labels, [&](std::uint32_t cluster, std::uint32_t vertex, double stop_above) {
    EXPECT_EQ(vertex, 1u);
    stops.push_back(stop_above);
    return cluster == 0 ? 5.0 : 2.0;
  });
  EXPECT_EQ(labels, (std::vector<std::uint32_t>{0, 2, 2, 1, 1}));
  // The second cluster is asked with the first one's error as its bound.
  ASSERT_EQ(stops.size(), 2u);
  EXPECT_EQ(stops[1], 5.0);
}

TEST(KeepClustersConnected, OfTwoEqualPiecesTheOneWithTheSmallerVertexStays) {
  std::vector<std::uint32_t> labels = {0, 1, 1, 0};
  keepClustersConnected(path(4), 2, labels, flat);
  EXPECT_EQ(labels, (std::vector<std::uint32_t>{0, 1, 1, 1}));
}

TEST(KeepClustersConnected, AComponentWithNoKeptPieceKeepsItsLabels) {
  // Two components, 0 - 1 and 2 - 3, both all cluster 0: the first is kept, and the second has
  // no kept neighbour to take a cluster from.
  VertexAdjacency a;
  a.offsets = {0, 1, 2, 3, 4};
  a.neighbours = {1, 0, 3, 2};
  std::vector<std::uint32_t> labels = {0, 0, 0, 0};
  keepClustersConnected(a, 1, labels, flat);
  EXPECT_EQ(labels, (std::vector<std::uint32_t>{0, 0, 0, 0}));
}

}  // namespace
}  // namespace odeskin
