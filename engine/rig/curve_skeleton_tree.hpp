// SPDX-License-Identifier: MIT
// The level graph (curve_skeleton_levels.hpp) as a tree hung from one region, with the bumps cut
// off: a leaf branch (tip region up to the first junction) shorter than `length`, or shorter than
// `radii` times the radius of the thin ring it starts from (thinner than `thin_radius`), is a bump
// on the surface (a knuckle, a toe, a fold), not a limb; its regions join the junction. A stubby
// branch on a thick ring (a chubby character's foot) is a limb. A
// contour that would close a cycle (a handle of a genus > 0 mesh, or two rings the level cut into
// one piece twice) is dropped, so each region is reached once.
#pragma once

#include <cstdint>
#include <vector>

#include "curve_skeleton_levels.hpp"

namespace odeskin {

struct LevelTree {
  std::uint32_t root = 0;                           // the region the tree hangs from
  std::vector<std::int32_t> parent_contour;          // per region: the contour towards the root; -1 at the root or unreached
  std::vector<std::vector<std::uint32_t>> children;  // per region: its kept contours away from the root
  std::vector<std::int32_t> child_region;            // per contour: the region away from the root; -1 if dropped
  std::vector<std::uint32_t> owner;                  // per region: itself, or the junction a pruned bump joined
  std::vector<char> reached;                         // per region: in the tree (1) or not
  std::size_t pruned_branches = 0;

  bool kept(std::uint32_t contour) const { return child_region[contour] >= 0; }
  // The region towards the root of a kept contour.
  std::uint32_t parentRegion(const LevelGraph& graph, std::uint32_t contour) const;
  // The mean radius of a region's kept rings (its skeleton node's thickness); `fallback` where it
  // keeps none.
  double ringRadius(const LevelGraph& graph, std::uint32_t region, double fallback) const;
};

struct PruneRule {
  double radii = 1.5;
  double length = 0.0;
  double thin_radius = 0.0;
};

LevelTree levelTree(const LevelGraph& graph, std::uint32_t root_region, const PruneRule& prune);

}  // namespace odeskin
