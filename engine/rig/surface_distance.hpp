// SPDX-License-Identifier: MIT
// Distances over a mesh from source vertices, for the curve rig's geodesic levels
// (curve_skeleton_levels.hpp): the fast marching method, Dijkstra over the edges, and breadth-first
// edge counts.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "../core/types.hpp"
#include "mesh_topology.hpp"

namespace odeskin {

constexpr double kUnreached = std::numeric_limits<double>::infinity();

// Distance over the surface from a set of source vertices (at their `initial` distances, 0 when
// empty): the fast marching method on triangles (Kimmel & Sethian 1998) with Dijkstra's edge step
// where a triangle gives no upwind update (obtuse corners, the first ring). Plain edge paths zig-zag
// on regular meshes (a ring grown on the cylinder's grid comes out V-shaped); the triangle update
// lets the front cross triangles straight. Vertices no edge path reaches keep kUnreached.
// Sources must be < the vertex count; initial, if given, one finite value >= 0 per source.
std::vector<double> surfaceDistance(const MeshTopology& mesh, std::span<const Vec3> positions,
                                    std::span<const std::uint32_t> sources, std::span<const double> initial = {});

// Dijkstra over the edges alone, every source at distance 0: cheaper than surfaceDistance and good
// enough where only the shape of the level tree matters (finding the body's centre).
std::vector<double> edgeDistance(const MeshTopology& mesh, std::span<const std::uint32_t> sources);

// Breadth-first edge counts from one vertex (-1: unreached): a cheap first sweep to an extremity.
std::vector<std::int32_t> edgeHops(const MeshTopology& mesh, std::uint32_t source);
// The sweep itself, into a caller's arrays: from `source` (hops[source] must be -1), every vertex
// reached through vertices whose hops are -1 gets its edge count from `source`. Returns how many
// it reached; queue[0, that count) holds them in the order of their counts (`queue` must hold
// hops.size() + 1 entries: the sweep writes one past the vertices it keeps). Vertices already
// counted stop the sweep, so one call per unreached vertex sweeps each connected component once.
std::size_t sweepEdgeHops(const MeshTopology& mesh, std::uint32_t source, std::span<std::int32_t> hops,
                          std::span<std::uint32_t> queue);

}  // namespace odeskin
