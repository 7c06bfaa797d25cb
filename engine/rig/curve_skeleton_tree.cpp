// SPDX-License-Identifier: MIT
#include "curve_skeleton_tree.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace odeskin {

std::uint32_t LevelTree::parentRegion(const LevelGraph& graph, std::uint32_t contour) const {
  const LevelContour& c = graph.contours[contour];
  return child_region[contour] == static_cast<std::int32_t>(c.upper) ? c.lower : c.upper;
}

double LevelTree::ringRadius(const LevelGraph& graph, std::uint32_t region, double fallback) const {
  double sum = 0.0;
  std::size_t n = 0;
  for (const std::uint32_t c : graph.regions[region].contours) {
    if (kept(c)) {
      sum += graph.contours[c].radius;
      ++n;
    }
  }
  return n > 0 ? sum / static_cast<double>(n) : fallback;
}

LevelTree levelTree(const LevelGraph& graph, std::uint32_t root_region, const PruneRule& prune) {
  const std::size_t r_count = graph.regions.size();
  LevelTree tree;
  tree.root = root_region;
  tree.parent_contour.assign(r_count, -1);
  tree.children.assign(r_count, {});
  tree.child_region.assign(graph.contours.size(), -1);
  tree.owner.resize(r_count);
  for (std::uint32_t r = 0; r < r_count; ++r) tree.owner[r] = r;
  tree.reached.assign(r_count, 0);

  // Breadth first: a contour leading to a region already reached would close a cycle.
  std::vector<std::uint32_t> order{root_region};
  tree.reached[root_region] = 1;
  for (std::size_t head = 0; head < order.size(); ++head) {
    const std::uint32_t r = order[head];
    for (const std::uint32_t c : graph.regions[r].contours) {
      if (static_cast<std::int32_t>(c) == tree.parent_contour[r]) continue;
      const LevelContour& contour = graph.contours[c];
      const std::uint32_t next = contour.lower == r ? contour.upper : contour.lower;
      if (tree.reached[next] || tree.child_region[c] >= 0) continue;
      tree.reached[next] = 1;
      tree.child_region[c] = static_cast<std::int32_t>(next);
      tree.parent_contour[next] = static_cast<std::int32_t>(c);
      tree.children[r].push_back(c);
      order.push_back(next);
    }
  }

  // Leaves first (reverse breadth-first order), so a junction's branches are judged before it.
  for (bool changed = true; changed;) {
    changed = false;
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
      const std::uint32_t tip = *it;
      if (tip == root_region || tree.owner[tip] != tip || !tree.children[tip].empty()) continue;
      // Walk up to the first region with another branch (or the root).
      std::vector<std::uint32_t> contours;
      std::uint32_t r = tip;
      double length = 0.0;
      Vec3 previous = graph.regions[tip].centroid;
      while (tree.parent_contour[r] >= 0) {
        const auto c = static_cast<std::uint32_t>(tree.parent_contour[r]);
        contours.push_back(c);
        length += glm::length(graph.contours[c].centroid - previous);
        previous = graph.contours[c].centroid;
        r = tree.parentRegion(graph, c);
        if (r == root_region || tree.children[r].size() > 1) break;
      }
      // The root's last branch is the whole mesh, never a bump.
      if (contours.empty() || (r == root_region && tree.children[r].size() <= 1)) continue;
      length += glm::length(graph.regions[r].centroid - previous);
      const double base_radius = graph.contours[contours.back()].radius;
      const bool bump = length < prune.length || (length < prune.radii * base_radius && base_radius < prune.thin_radius);
      if (!bump) continue;
      // A bump: its regions join the junction r, its contours leave the tree.
      for (const std::uint32_t c : contours) {
        const auto below = static_cast<std::uint32_t>(tree.child_region[c]);
        tree.owner[below] = r;
        tree.child_region[c] = -1;
      }
      auto& kids = tree.children[r];
      kids.erase(std::find(kids.begin(), kids.end(), contours.back()));
      ++tree.pruned_branches;
      changed = true;
    }
  }
  // Owners of owners: a bump pruned onto a region that was itself pruned later.
  for (std::uint32_t r = 0; r < r_count; ++r) {
    std::uint32_t o = tree.owner[r];
    while (tree.owner[o] != o) o = tree.owner[o];
    tree.owner[r] = o;
  }
  return tree;
}

}  // namespace odeskin
