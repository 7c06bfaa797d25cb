// SPDX-License-Identifier: MIT
// Every vertex's binding (curve a, curve b, w, v) (PIPELINE.md 3). A vertex of a part lies between
// two consecutive planes of the part's sequence, extended at each end by the nearest aligned curve
// of a neighbouring part so that junctions blend across the seam: d_a = n_a . (x - o_a) >= 0 >=
// d_b and w = d_a / (d_a - d_b). Beyond the sequence (tips, rims) it takes the nearest plane's
// curve alone (w = 0). A part without curves (too small, or cut into scraps) lends its vertices to
// the part reached first along mesh edges (Dijkstra); a vertex no edge connects to a curved part
// goes to the nearest curve point. v is the arc-length parameter of the nearest point of each
// curve to the vertex moved along the plane normal onto the curve's plane, blended by w (across
// the wrap-around of closed curves); where the two parameters differ by more than 0.1 one v
// cannot serve both curves and the nearer curve is used alone.
#pragma once

#include <span>
#include <vector>

#include "../core/types.hpp"
#include "../mesh/adjacency.hpp"
#include "part_curves.hpp"
#include "part_segmentation.hpp"

namespace odeskin {

// How each vertex's pair of planes and nearest curve points are found: pruned (vertices in small
// clusters that rule out most pairs at once; each curve's segments behind bounding balls, or a
// bounding-box tree for a very long curve), or
// by scanning every pair and every segment, the reference the tests hold the pruned search to.
// Both give the same bindings, bit for bit; the scans cost O(V sqrt V) on refined meshes.
// kPrunedTrees: the pruned search with every curve's segments searched through a tree (the default
// uses trees only for curves too long to scan), so that the tests hold both searches to the scans.
enum class BindingSearch { kPruned, kPrunedTrees, kExhaustive };

// `layout`: compacted, every curve oriented, at least one curve. One binding per vertex.
std::vector<CurveBinding> bindVertices(std::span<const Vec3> rest, const VertexAdjacency& adjacency,
                                       const Segmentation& seg, const CurveLayout& layout, double spacing,
                                       BindingSearch search = BindingSearch::kPruned);

}  // namespace odeskin
