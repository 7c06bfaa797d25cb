// SPDX-License-Identifier: MIT
#include "cluster_connectivity.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace odeskin {

void keepClustersConnected(const VertexAdjacency& adjacency, std::size_t clusters, std::vector<std::uint32_t>& labels,
                           const ClusterCost& cost) {
  const std::size_t v_count = labels.size();
  std::vector<std::uint32_t> piece(v_count, UINT32_MAX);
  std::vector<std::size_t> piece_size;
  std::vector<std::uint32_t> stack;
  for (std::uint32_t s = 0; s < v_count; ++s) {
    if (piece[s] != UINT32_MAX) continue;
    const auto id = static_cast<std::uint32_t>(piece_size.size());
    std::size_t size = 0;
    piece[s] = id;
    stack.assign(1, s);
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      ++size;
      for (const std::uint32_t j : adjacency.of(i)) {
        if (piece[j] == UINT32_MAX && labels[j] == labels[i]) {
          piece[j] = id;
          stack.push_back(j);
        }
      }
    }
    piece_size.push_back(size);
  }
  std::vector<std::uint32_t> main_piece(clusters, UINT32_MAX);
  for (std::uint32_t i = 0; i < v_count; ++i) {
    std::uint32_t& best = main_piece[labels[i]];
    if (best == UINT32_MAX || piece_size[piece[i]] > piece_size[best]) best = piece[i];
  }
  std::vector<char> orphan(v_count, 0);
  std::vector<std::uint32_t> orphans;
  for (std::uint32_t i = 0; i < v_count; ++i) {
    if (piece[i] != main_piece[labels[i]]) {
      orphan[i] = 1;
      orphans.push_back(i);
    }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> wave;  // (vertex, new label)
  while (!orphans.empty()) {
    wave.clear();
    for (const std::uint32_t i : orphans) {
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
    std::erase_if(orphans, [&](std::uint32_t i) { return !orphan[i]; });
  }
}

}  // namespace odeskin
