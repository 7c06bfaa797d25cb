// SPDX-License-Identifier: MIT
// Iso-parametric curves of a rigged mesh (thesis 6.3.1 and 5.3): segment the mesh into parts by
// dominant bone, find the seam curves between parts, cut each part with planes (centroid-following
// for one seam, dichotomy refinement for two, clustering for more), snap intersection points to
// edge ends within the threshold of thesis Fig. 6.4, and bind every vertex to the two curves
// around it. Quad-dominant meshes can use edge loops instead (thesis 5.3).
#pragma once

#include <span>

#include "../core/result.hpp"
#include "../rig/rig.hpp"
#include "curve_set.hpp"

namespace odeskin {

enum class CurveMethod {
  kAuto,        // edge loops on quad-dominant meshes (>= 80% quads; cuts if they give no ring), plane cuts otherwise
  kPlaneCuts,
  kEdgeLoops,
};

struct CurveOptions {
  CurveMethod method = CurveMethod::kAuto;
  double spacing = 0.0;          // distance between cuts along a part; 0: ~3 mean edge lengths
  double snap_threshold = 0.25;  // snap a cut point to an edge end closer than this x edge length
  int min_points = 8;            // curves with fewer points are dropped (their vertices bind to neighbours)
};

// Every vertex gets a binding (validateCurveSet holds on the result). rest: the bind mesh;
// influences: V rows over skeleton bones (dominant bone = part). Errors: kInvalidArgument for
// sizes or non-manifold faces (naming the face), kDegenerate for a mesh no curve can be cut on.
//
// Choices the thesis leaves open (details in the files named):
// - Parts (part_segmentation): each connected patch of one dominant bone is its own part (IsoCurve::part
//   is its bone, so two patches of one bone share per-part materials); patches with fewer than
//   2 x min_points vertices join the neighbour they share most edges with.
// - Cuts (part_planes, plane_cuts): each plane keeps one chain, the one with the most points on
//   the part's own edges, then the longest; cuts may run two edges past the part so that rings
//   close where a neighbour's patch reaches thinly around a limb. A seam's cut is one curve
//   shared by both parts. Open mesh rims with >= min_points vertices end their part's sequence.
// - v (curve_orientation): neighbouring curves of a part run the same way round and start on one
//   carried reference direction; bindings (vertex_binding) blend two curves only where the
//   vertex's parameters on both agree within 0.1, and otherwise use the nearer curve alone (w = 0).
//   Vertices beyond a part's first or last curve (tips) take that curve alone.
// options: spacing >= 0, snap_threshold in [0, 0.5), min_points >= 3 (kInvalidArgument otherwise).
Result<CurveSet> buildIsoCurves(std::span<const Vec3> rest, const FaceList& faces, const Skeleton& skeleton,
                                const Influences& influences, const CurveOptions& options = {});

}  // namespace odeskin
