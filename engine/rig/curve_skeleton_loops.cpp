// SPDX-License-Identifier: MIT
// The curve skeleton of a quad-dominant mesh from its own edge loops (thesis 5.3): the ray-and-fan
// test (curves/ray_fan_directions.hpp) tells every quad edge axial or circumferential, and the
// closed straight edge walks that run around the limbs are the iso-parametric curves, exactly on
// the mesh's vertices. The level tree still gives the parts (which branch a ring is on, where
// the junctions and tips are) and the geodesic distance orders the rings along each part; the
// loops replace only the rings of the levels.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "../curves/ray_fan_directions.hpp"
#include "../mesh/poly_mesh.hpp"
#include "curve_skeleton_parts.hpp"

namespace odeskin {
namespace {

// A ring needs this many vertices (a coarser loop is not round enough for its centroid to be on
// the axis).
constexpr std::size_t kMinRingPoints = 6;
// Decided ray-and-fan votes per edge loop: a loop's class is its majority, so a few vertices
// spread along it decide it (RayFanOptions::loop_samples) instead of every vertex.
constexpr int kLoopSamples = 3;

}  // namespace

Result<CurveSkeleton> skeletonFromEdgeLoops(std::span<const Vec3> rest, const FaceList& faces, const LevelGraph& graph,
                                            const LevelTree& tree, const TreeParts& parts, std::span<const double> f,
                                            const MeshTopology& mesh, std::span<const SkeletonAnchor> root_anchors,
                                            std::vector<IsoCurve>& curves, EdgeLoopStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  ODESKIN_ASSIGN_OR_RETURN(PolyMesh poly, buildPolyMesh(rest, faces, "curve skeleton"));
  RayFanOptions options;
  options.loop_samples = kLoopSamples;
  const RayFanDirections directions = rayFanDirections(poly, options);
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
  // A quad mesh has a ring per edge row; the skeleton takes one per level spacing (two edge rows,
  // as the geodesic rings), the ring nearest the middle of its slab, so that the turn test's
  // windows see as many rings as on the levels rather than twice as many noisier ones.
  struct Pick {
    std::size_t loop = 0;
    double off_centre = 0.0;
  };
  std::map<std::pair<std::uint32_t, std::int64_t>, Pick> picks;  // (part, slab) -> ring
  std::vector<std::size_t> votes(parts.parts.size(), 0);
  std::vector<std::uint32_t> loop_part(loops.rings.size(), 0);
  for (std::size_t l = 0; l < loops.rings.size(); ++l) {
    const EdgeLoop& loop = loops.rings[l];
    std::fill(votes.begin(), votes.end(), 0);
    double key = 0.0;
    for (const std::uint32_t v : loop.vertices) {
      ++votes[parts.vertex_parts[v]];
      key += f[v];
    }
    key /= static_cast<double>(loop.vertices.size());
    if (!std::isfinite(key)) continue;  // another component than the rigged one
    loop_part[l] = static_cast<std::uint32_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    const double slab = std::floor(key / graph.spacing);
    const double off_centre = std::abs(key - (slab + 0.5) * graph.spacing);
    const auto [it, inserted] = picks.try_emplace({loop_part[l], static_cast<std::int64_t>(slab)}, Pick{l, off_centre});
    if (!inserted && off_centre < it->second.off_centre) it->second = Pick{l, off_centre};
  }
  std::vector<IsoCurve> found;
  found.reserve(picks.size());
  for (const auto& [where, pick] : picks) {
    IsoCurve curve;
    curve.closed = true;
    for (const std::uint32_t v : loops.rings[pick.loop].vertices) curve.points.push_back({v, v, 0.0});
    curve.part = loop_part[pick.loop];
    found.push_back(std::move(curve));
  }
  stats.seconds_loops = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return skeletonFromPartCurves(rest, graph, tree, parts, f, mesh, root_anchors, found, curves);
}

}  // namespace odeskin
