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
  kAuto,        // edge loops on quad-dominant meshes, plane cuts otherwise
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
Result<CurveSet> buildIsoCurves(std::span<const Vec3> rest, const FaceList& faces, const Skeleton& skeleton,
                                const Influences& influences, const CurveOptions& options = {});

}  // namespace odeskin
