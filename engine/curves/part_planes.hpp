// SPDX-License-Identifier: MIT
// Where each body part is cut (thesis 6.3.1). A part with one seam (a hand, the head, a tail) is
// cut by planes that follow the centroids of the previous cuts away from the seam; a part between
// two seams (a forearm) by dichotomy: the plane halfway between two cuts, its normal the mean of
// theirs, recursively, until cuts are one spacing apart; a part with more seams (a torso) has its
// seams clustered into two groups along its axis, dichotomy between the groups and centroid
// following beyond them. Every seam's own plane gives one curve, shared by both parts it joins.
// Open mesh boundaries (a tube's rim, a hole at the end of a limb) end their part's sequence.
#pragma once

#include <span>
#include <vector>

#include "../core/types.hpp"
#include "../mesh/adjacency.hpp"
#include "part_curves.hpp"
#include "part_segmentation.hpp"
#include "plane_cuts.hpp"

namespace odeskin {

struct PlaneCutOptions {
  double spacing = 0.0;  // > 0, distance between cuts
  double snap_threshold = 0.25;
  std::size_t min_points = 8;
  std::size_t region_scans_before_tree = CutRegion::kScansBeforeTree;  // see CutRegion (the same cuts either way)
};

// Curves and per-part station sequences (normals along each part's flow, not yet oriented).
CurveLayout planeCutCurves(std::span<const Vec3> rest, const CutMesh& mesh, const VertexAdjacency& adjacency,
                           const Segmentation& seg, const PlaneCutOptions& options);

// Appends each open boundary loop with >= min_points vertices to the start or end of its part's
// sequence when it lies beyond that end and faces along the flow (dropping stations it overtakes).
void addBoundaryLoops(std::span<const Vec3> rest, const std::vector<std::vector<std::uint32_t>>& loops,
                      const Segmentation& seg, double spacing, std::size_t min_points, CurveLayout& layout);

}  // namespace odeskin
