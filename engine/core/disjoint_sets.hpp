// SPDX-License-Identifier: MIT
// Union-find over indices 0..n-1 with path halving. The root of a set is its smallest member, so
// numbering sets by their roots is deterministic (part segmentation and the curve rig's level
// rings both rely on that).
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace odeskin {

struct DisjointSets {
  std::vector<std::uint32_t> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  // Points every member straight at its root, so that parent[x] is find(x) until the next unite:
  // one pass in index order suffices, since a member's parent is never above it (unite links the
  // larger root to the smaller; halving only moves a parent down).
  void flatten() {
    for (std::size_t x = 0; x < parent.size(); ++x) parent[x] = parent[parent[x]];
  }
};

}  // namespace odeskin
