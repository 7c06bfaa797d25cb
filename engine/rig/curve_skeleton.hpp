// SPDX-License-Identifier: MIT
// The curve skeleton of a mesh (thesis 5.3): the centroids of its iso-parametric curves, joined
// along each body part, the parts meeting at junction points where a limb leaves the body.
//
// The thesis reads the curves off a quad mesh its designer laid out; an arbitrary triangle mesh
// has none, and odeskin's curve identification (curves/iso_curves.hpp) needs body parts first. So:
//  1. Parts from geometry alone (curve_skeleton_levels.hpp): rings of a geodesic distance, whose
//     graph is a tree of tubes and junctions. The distance is measured twice: coarsely along
//     edges from an extremity (the far end of a sweep from any vertex), then by fast marching
//     from a plane band across the body at the centre of that first tree, so that rings run
//     across the body and its limbs (a ring grown from a point on a torso first spreads over its
//     surface as a disc). Short branches off thin rings are bumps and are pruned
//     (curve_skeleton_tree.hpp).
//  2. Curves: with CurveSource::kLevels (what kAuto, the default, takes on triangle meshes) the
//     geodesic rings themselves; with kPlaneCuts the existing identification cuts each part (a
//     branch of the tree) with planes across it (centroid-following, dichotomy between seams), the
//     curves odeskin binds vertices to; with kEdgeLoops (kAuto on quad-dominant meshes) the quad
//     edge loops the ray-and-fan test calls circumferential (curves/ray_fan_directions.hpp). On
//     the shared data the rings give skeletons closer to the ground truth than the cuts, in a
//     fraction of the time (docs/rigging.md).
//  3. Nodes: every curve's length-weighted centroid; a junction region's centroid where branches
//     meet (the seam curves of the limbs that leave there are its children); at each free end the
//     centroid of the cap beyond the last ring. Node 0 is the centre ring of step 1.
// Every node is a weighted mean of points on mesh edges (SkeletonAnchor), so the same skeleton
// follows any pose of the mesh (curveSkeletonPositions): what the bend-angle test of several
// example poses needs (thesis 5.4).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "../core/iso_curve.hpp"
#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

enum class CurveSource {
  kLevels,     // the geodesic rings (closer to the ground-truth skeletons than the cuts and faster, docs/rigging.md)
  kPlaneCuts,  // curves/iso_curves.hpp on the geodesic parts (the curves odeskin fits)
  kEdgeLoops,  // the mesh's own quad edge loops around the limbs (ray-and-fan test, curves/ray_fan_directions.hpp)
  kAuto,       // kEdgeLoops on a quad-dominant mesh (>= 80% quads), else kLevels (default)
};

// What kAuto picks for these faces.
CurveSource resolveCurveSource(CurveSource source, const FaceList& faces);

enum class SkeletonNodeKind : std::uint8_t {
  kRoot,      // the centre ring's slab
  kCurve,     // a curve's centroid
  kJunction,  // where three or more branches meet
  kTip,       // the cap beyond a branch's last curve
};

struct SkeletonAnchor {
  CurvePoint point;
  double weight = 0.0;
};

struct CurveSkeleton {
  std::vector<Vec3> positions;             // N, on the mesh the skeleton was built from
  std::vector<double> radii;               // N: mean distance of the node's curve from it
  std::vector<SkeletonNodeKind> kinds;     // N
  std::vector<std::int32_t> parents;       // N: towards node 0 (-1 there); a parent precedes its children
  std::vector<std::uint32_t> parts;        // N: the body part (branch) each node lies on
  std::vector<std::uint32_t> anchor_offsets{0};  // N + 1
  std::vector<SkeletonAnchor> anchors;     // node n: the weighted mean of [offsets[n], offsets[n+1])

  std::size_t nodeCount() const { return positions.size(); }
};

// Every node's position on `pose` (same vertices as the mesh the skeleton was built from).
std::vector<Vec3> curveSkeletonPositions(const CurveSkeleton& skeleton, std::span<const Vec3> pose);

struct CurveSkeletonOptions {
  CurveSource source = CurveSource::kAuto;
  double level_spacing = 0.0;    // distance between geodesic levels; 0: 2 mean edge lengths, at most 1/50 of the box diagonal
  double prune_fraction = 0.04;       // a leaf branch shorter than this x the box diagonal is a bump,
  double prune_radii = 1.5;           // ... and one shorter than this x its base ring's radius
  double prune_thin_fraction = 0.03;  // ... when that ring is thinner than this x the box diagonal
};

struct CurveSkeletonResult {
  CurveSkeleton skeleton;
  std::vector<IsoCurve> curves;             // the curves whose centroids the nodes are (part = body part)
  std::vector<std::uint32_t> vertex_parts;  // V: each vertex's body part
  std::size_t part_count = 0;
  std::size_t pruned_branches = 0;
  std::size_t unreached_vertices = 0;        // in other connected components than the largest (not rigged)
  CurveSource source = CurveSource::kLevels;  // what was used: kLevels when the plane cuts or edge loops failed
  std::string note;                          // why the plane cuts or edge loops were not used, if they were asked for
  // kEdgeLoops: the ray-and-fan test's edge classes and the loops it gave.
  std::size_t axial_edges = 0;
  std::size_t circumferential_edges = 0;
  std::size_t unknown_edges = 0;
  std::size_t edge_loop_rings = 0;  // closed circumferential loops (the curves, before the tree drops any)
  std::size_t axial_lines = 0;      // loops running along the limbs
  // Table 5.1's two stages: finding the curves (geodesic levels, and plane cuts if asked) and
  // making the skeleton from them (tree, pruning, centroids).
  // The mesh's edges and triangle neighbours are built first (seconds_topology, not counted in
  // either: a mesh loaded once has them).
  double seconds_topology = 0.0;
  double seconds_curves = 0.0;
  double seconds_skeleton = 0.0;
  // seconds_curves' parts for the levels: the body's centre and its shortest section (the band),
  // the first pass's edge distances and coarse level graph (with its tree, centre and band; both 0
  // unless the section failed), the fast marching from the band, and the fine level graph with its
  // tree and parts. The plane cuts or edge loops, if used, are the rest.
  double seconds_centre = 0.0;
  double seconds_edge_distance = 0.0;
  double seconds_coarse_levels = 0.0;
  double seconds_marching = 0.0;
  double seconds_fine_levels = 0.0;
  double seconds_edge_loops = 0.0;  // kEdgeLoops: the half-edge mesh, the ray-and-fan test and the loop walk
};

// rest: the mesh (>= 4 vertices, finite); faces: valid, manifold polygons over it.
// kInvalidArgument naming the vertex or face: sizes, non-finite positions, indices out of range,
// a face with fewer than 3 corners; kDegenerate: no edge of non-zero length, or no ring (a mesh too
// small or too flat for levels), naming the spacing.
Result<CurveSkeletonResult> buildCurveSkeleton(std::span<const Vec3> rest, const FaceList& faces,
                                               const CurveSkeletonOptions& options = {});

}  // namespace odeskin
