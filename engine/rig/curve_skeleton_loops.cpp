// SPDX-License-Identifier: MIT
// The curve skeleton of a quad-dominant mesh from its own edge loops (thesis 5.3): the ray-and-fan
// test (curves/ray_fan_directions.hpp) tells every quad edge axial or circumferential, and the
// closed straight edge walks that run around the limbs are the iso-parametric curves, exactly on
// the mesh's vertices. The level tree still gives the parts (which branch a ring is on, where
// the junctions and tips are) and the geodesic distance orders the rings along each part; the
// loops replace only the rings of the levels.
#include <algorithm>
#include <chrono>

#include "../curves/ray_fan_directions.hpp"
#include "../mesh/poly_mesh.hpp"
#include "curve_skeleton_parts.hpp"

namespace odeskin {
namespace {

// A ring needs this many vertices (a coarser loop is not round enough for its centroid to be on
// the axis).
constexpr std::size_t kMinRingPoints = 6;

}  // namespace

Result<CurveSkeleton> skeletonFromEdgeLoops(std::span<const Vec3> rest, const FaceList& faces, const LevelGraph& graph,
                                            const LevelTree& tree, const TreeParts& parts, std::span<const double> f,
                                            const MeshTopology& mesh, std::span<const SkeletonAnchor> root_anchors,
                                            std::vector<IsoCurve>& curves, EdgeLoopStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  ODESKIN_ASSIGN_OR_RETURN(PolyMesh poly, buildPolyMesh(rest, faces, "curve skeleton"));
  const RayFanDirections directions = rayFanDirections(poly);
  DirectedLoops loops = directedEdgeLoops(poly, directions, kMinRingPoints);
  stats.axial_edges = directions.axial_edges;
  stats.circumferential_edges = directions.circumferential_edges;
  stats.unknown_edges = directions.unknown_edges;
  stats.measured_vertices = directions.measured_vertices;
  stats.rings = loops.rings.size();
  stats.axial_lines = loops.axial.size();
  if (loops.rings.empty()) {
    return degenerate("no closed edge loop of " + std::to_string(kMinRingPoints) +
                      " vertices or more runs around a limb (ray-and-fan test: " + std::to_string(directions.circumferential_edges) +
                      " circumferential, " + std::to_string(directions.axial_edges) + " axial, " +
                      std::to_string(directions.unknown_edges) + " undecided edges)");
  }
  std::vector<IsoCurve> found;
  found.reserve(loops.rings.size());
  std::vector<std::size_t> votes(parts.parts.size(), 0);
  for (const EdgeLoop& loop : loops.rings) {
    IsoCurve curve;
    curve.closed = true;
    std::fill(votes.begin(), votes.end(), 0);
    for (const std::uint32_t v : loop.vertices) {
      curve.points.push_back({v, v, 0.0});
      ++votes[parts.vertex_parts[v]];
    }
    curve.part = static_cast<std::uint32_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    found.push_back(std::move(curve));
  }
  stats.seconds_loops = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return skeletonFromPartCurves(rest, graph, tree, parts, f, mesh, root_anchors, found, curves);
}

}  // namespace odeskin
