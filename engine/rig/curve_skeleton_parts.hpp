// SPDX-License-Identifier: MIT
// Body parts of the level tree and the pieces both curve sources share (internal to the curve
// skeleton): a part is a branch of the tree, from the root or a junction to the next junction or
// a tip; a junction region belongs to the branch arriving at it, a pruned bump to its junction.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "curve_skeleton.hpp"
#include "curve_skeleton_levels.hpp"
#include "curve_skeleton_tree.hpp"

namespace odeskin {

struct TreePart {
  std::uint32_t start_region = 0;  // the root or a junction
  std::int32_t end_region = -1;    // a junction or a tip region (-1: none yet)
  std::int32_t parent = -1;        // the part the start region belongs to (-1 for the first)
  std::uint32_t depth = 0;         // parts between it and the root
};

struct TreeParts {
  std::vector<TreePart> parts;               // in breadth-first order: a parent precedes its children
  std::vector<std::int32_t> contour_part;    // per contour (-1: not in the tree)
  std::vector<std::int32_t> region_part;     // per region (-1: not reached)
  std::vector<std::uint32_t> vertex_parts;   // V (unreached vertices: part 0)
};

TreeParts treeParts(const LevelGraph& graph, const LevelTree& tree);

// How a region of the tree shows in the skeleton: the root, a junction (>= 2 branches away from
// the root), a tip (none), or nothing (a piece of a tube between two rings).
SkeletonNodeKind regionKind(const LevelTree& tree, std::uint32_t region, bool* has_node);

// Appends a node whose position (and anchors) is the weighted mean of `anchors` on `rest`.
void addSkeletonNode(CurveSkeleton& s, SkeletonNodeKind kind, std::int32_t parent, std::uint32_t part, double radius,
                     std::span<const SkeletonAnchor> anchors, std::span<const Vec3> rest);
// Appends a curve's node: its anchors are the curve's points, each weighted by half the length of
// the segments it ends (all 1 if the curve has no length), so the node is the length-weighted centroid.
void addCurveNode(CurveSkeleton& s, SkeletonNodeKind kind, std::int32_t parent, std::uint32_t part, double radius,
                  std::span<const CurvePoint> points, bool closed, std::span<const Vec3> rest);

// A region's anchors: its own vertices (weight 1 each).
std::vector<SkeletonAnchor> regionAnchors(const LevelGraph& graph, std::uint32_t region);
// A tip's anchors: where its cap is open (a tube's rim, a hole at the end of a limb) the whole
// rim's vertices (the boundary loops it touches), whose centre is the end of the limb; otherwise
// the cap's vertices.
std::vector<SkeletonAnchor> tipAnchors(const LevelGraph& graph, std::uint32_t region, const MeshTopology& mesh);

// The contour's points in order along it (a closed one from point 0, an open one from an end).
IsoCurve orderedContour(const LevelContour& contour, std::uint32_t part);

// The root node is `root_anchors` (the band the distance grew from). The plane-cut curves of the parts (curves/iso_curves.hpp) as skeleton nodes; `f` orders them
// along each part; `seconds_cuts` receives the time buildIsoCurves took. Errors: buildIsoCurves'
// (the caller falls back to the rings).
Result<CurveSkeleton> skeletonFromPlaneCuts(std::span<const Vec3> rest, const FaceList& faces, const LevelGraph& graph,
                                            const LevelTree& tree, const TreeParts& parts, std::span<const double> f,
                                            const MeshTopology& mesh, std::span<const SkeletonAnchor> root_anchors,
                                            std::vector<IsoCurve>& curves, double& seconds_cuts);

// The skeleton from curves found on the mesh (plane cuts, quad edge loops): each curve goes to the
// deepest part it touches (a seam curve starts the limb), `f` orders a part's curves, and closed
// ones become nodes chained from the part's start region to its end region. found[c].part: the
// caller's guess of the curve's part (out of range: 0); the curves used are appended to `curves`.
CurveSkeleton skeletonFromPartCurves(std::span<const Vec3> rest, const LevelGraph& graph, const LevelTree& tree,
                                     const TreeParts& parts, std::span<const double> f, const MeshTopology& mesh,
                                     std::span<const SkeletonAnchor> root_anchors, std::vector<IsoCurve>& found,
                                     std::vector<IsoCurve>& curves);

// The curve skeleton from the quad edge loops the ray-and-fan test calls circumferential
// (curves/ray_fan_directions.hpp) on the level tree's parts; `stats` receives the edge counts.
// kDegenerate when no loop is a ring (the caller falls back to the levels).
struct EdgeLoopStats {
  std::size_t axial_edges = 0;
  std::size_t circumferential_edges = 0;
  std::size_t unknown_edges = 0;
  std::size_t measured_vertices = 0;
  std::size_t rings = 0;
  std::size_t axial_lines = 0;
  double seconds_loops = 0.0;  // ray-and-fan test and loop walk
};
Result<CurveSkeleton> skeletonFromEdgeLoops(std::span<const Vec3> rest, const FaceList& faces, const LevelGraph& graph,
                                            const LevelTree& tree, const TreeParts& parts, std::span<const double> f,
                                            const MeshTopology& mesh, std::span<const SkeletonAnchor> root_anchors,
                                            std::vector<IsoCurve>& curves, EdgeLoopStats& stats);

}  // namespace odeskin
