// SPDX-License-Identifier: MIT
#include "cluster_connectivity.hpp"

#include <cstdint>
#include <limits>

#include "../core/disjoint_sets.hpp"

namespace odeskin {

void keepClustersConnected(const VertexAdjacency& adjacency, std::size_t clusters, std::vector<std::uint32_t>& labels,
                           const ClusterCost& cost) {
  const std::size_t v_count = labels.size();
  // A cluster's pieces: its vertices joined along edges inside it. Each is named by its smallest
  // vertex (DisjointSets' roots), so an equal size goes to the piece met first in vertex order.
  DisjointSets pieces(v_count);
  for (std::uint32_t i = 0; i < v_count; ++i) {
    const std::uint32_t label = labels[i];
    for (const std::uint32_t j : adjacency.of(i)) {
      if (j > i && labels[j] == label) pieces.unite(i, j);
    }
  }
  pieces.flatten();
  const std::vector<std::uint32_t>& piece = pieces.parent;
  std::vector<std::uint32_t> piece_size(v_count, 0);
  for (std::uint32_t i = 0; i < v_count; ++i) ++piece_size[piece[i]];
  std::vector<std::uint32_t> main_piece(clusters, UINT32_MAX);
  for (std::uint32_t i = 0; i < v_count; ++i) {
    std::uint32_t& best = main_piece[labels[i]];
    if (best == UINT32_MAX || piece_size[piece[i]] > piece_size[best]) best = piece[i];
  }
  std::vector<char> orphan(v_count, 0);
  std::vector<std::uint32_t> candidates;  // the orphans a wave examines; the first wave, all of them
  for (std::uint32_t i = 0; i < v_count; ++i) {
    if (piece[i] != main_piece[labels[i]]) {
      orphan[i] = 1;
      candidates.push_back(i);
    }
  }
  // A wave settles every orphan beside a vertex that is not one, each from the labels before the
  // wave. An orphan a wave did not settle sees the same neighbours in the next wave unless one of
  // them was just settled, so each later wave examines only the orphans beside the last wave's:
  // the same waves as examining every orphan every time, without rescanning a deep region of
  // orphans once per wave.
  std::vector<std::uint32_t> queued(v_count, 0);  // the wave that last queued the vertex
  std::uint32_t wave_number = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> wave;  // (vertex, new label)
  while (!candidates.empty()) {
    wave.clear();
    for (const std::uint32_t i : candidates) {
      double best_error = std::numeric_limits<double>::infinity();
      std::uint32_t best = UINT32_MAX;
      for (const std::uint32_t j : adjacency.of(i)) {
        if (orphan[j] || labels[j] == best) continue;
        const double e = cost(labels[j], i, best_error);
        if (e < best_error) {
          best_error = e;
          best = labels[j];
        }
      }
      if (best != UINT32_MAX) wave.emplace_back(i, best);
    }
    // A mesh component holding no kept piece keeps its labels.
    if (wave.empty()) break;
    for (const auto& [i, label] : wave) {
      labels[i] = label;
      orphan[i] = 0;
    }
    ++wave_number;
    candidates.clear();
    for (const auto& [i, label] : wave) {
      for (const std::uint32_t j : adjacency.of(i)) {
        if (orphan[j] && queued[j] != wave_number) {
          queued[j] = wave_number;
          candidates.push_back(j);
        }
      }
    }
  }
}

}  // namespace odeskin
