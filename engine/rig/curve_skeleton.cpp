// SPDX-License-Identifier: MIT
#include "curve_skeleton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <glm/geometric.hpp>

#include "../core/number_text.hpp"
#include "../core/position_box.hpp"
#include "../curves/edge_loops.hpp"
#include "body_section.hpp"
#include "curve_skeleton_levels.hpp"
#include "curve_skeleton_parts.hpp"
#include "curve_skeleton_tree.hpp"
#include "mesh_topology.hpp"
#include "surface_distance.hpp"

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

// Levels every 2 mean edge lengths: a ring per two edge rows places junctions to within an edge or
// two. Coarse meshes (the 20-sided cylinder) get at least 50 levels across their box diagonal, so
// that joints can be placed finer than their edges (the cut points are exact on the edges).
constexpr double kDefaultSpacingEdges = 2.0;
constexpr double kMinLevelsPerDiagonal = 50.0;
// The first pass only finds the body's centre: levels this many times farther apart.
constexpr double kFirstPassSpacing = 3.0;
// CurveSource::kAuto takes the quad edge loops when at least this fraction of the faces are quads
// (as buildIsoCurves' CurveMethod::kAuto).
constexpr double kQuadDominant = 0.8;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The input's errors, or the rest mesh's bounding box.
Result<PositionBox> checkInput(std::span<const Vec3> rest, const FaceList& faces, const CurveSkeletonOptions& options) {
  if (rest.size() < 4) return invalidArgument("curve skeleton: the mesh has " + std::to_string(rest.size()) + " vertices, needs at least 4");
  ODESKIN_ASSIGN_OR_RETURN(PositionBox box, checkedPositionBox(rest, "curve skeleton"));
  if (faces.face_offsets.empty() || faces.face_offsets.front() != 0 || faces.face_offsets.back() != faces.indices.size() ||
      !std::is_sorted(faces.face_offsets.begin(), faces.face_offsets.end())) {
    return invalidArgument("curve skeleton: face offsets are not a compressed row layout of the face indices");
  }
  if (faces.faceCount() == 0) return invalidArgument("curve skeleton: the mesh has no faces");
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    if (faces.face_offsets[f + 1] - faces.face_offsets[f] < 3) {
      return invalidArgument("curve skeleton: face " + std::to_string(f) + " has fewer than 3 corners");
    }
    for (std::uint32_t k = faces.face_offsets[f]; k < faces.face_offsets[f + 1]; ++k) {
      if (faces.indices[k] >= rest.size()) {
        return invalidArgument("curve skeleton: face " + std::to_string(f) + " uses vertex " + std::to_string(faces.indices[k]) +
                               " of " + std::to_string(rest.size()));
      }
    }
  }
  if (!(options.level_spacing >= 0.0) || !std::isfinite(options.level_spacing)) {
    return invalidArgument("curve skeleton: level spacing must be a finite number >= 0 (0: automatic)");
  }
  if (!(options.prune_radii >= 0.0) || !std::isfinite(options.prune_radii) || !(options.prune_fraction >= 0.0) ||
      !(options.prune_fraction < 1.0) || !(options.prune_thin_fraction >= 0.0) || !(options.prune_thin_fraction < 1.0)) {
    return invalidArgument("curve skeleton: prune_radii must be >= 0, prune_fraction and prune_thin_fraction in [0, 1)");
  }
  return box;
}

// Position order, for ties that must not depend on how the vertices are numbered.
bool positionBefore(const Vec3& p, const Vec3& q) {
  if (p.x != q.x) return p.x < q.x;
  if (p.y != q.y) return p.y < q.y;
  return p.z < q.z;
}

// The vertices of the largest connected component (rigging is for one connected surface; the
// first such component in vertex order on a tie).
std::vector<std::uint32_t> largestComponent(const MeshTopology& mesh) {
  const std::size_t count = mesh.vertex_offsets.size() - 1;
  std::vector<std::int32_t> hops(count, -1);
  std::vector<std::uint32_t> queue(count + 1);
  std::vector<std::uint32_t> largest;
  for (std::uint32_t s = 0; s < count; ++s) {
    if (hops[s] >= 0) continue;
    const std::size_t reached = sweepEdgeHops(mesh, s, hops, queue);
    if (reached > largest.size()) largest.assign(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(reached));
  }
  return largest;
}

// The vertex of the component farthest by `measure`, ties by position.
template <typename Measure>
std::uint32_t farthestVertex(std::span<const Vec3> rest, std::span<const std::uint32_t> component, Measure&& measure) {
  std::uint32_t best = component.front();
  double best_measure = -std::numeric_limits<double>::infinity();
  for (const std::uint32_t v : component) {
    const double m = measure(v);
    if (m > best_measure || (m == best_measure && positionBefore(rest[v], rest[best]))) {
      best_measure = m;
      best = v;
    }
  }
  return best;
}

// The first pass's source: the far end, along edges, of the vertex farthest from the component's
// box centre. Chosen by the shape, so that the fallback band does not depend on the numbering.
std::uint32_t componentExtremity(std::span<const Vec3> rest, const MeshTopology& mesh,
                                 std::span<const std::uint32_t> component) {
  Vec3 low = rest[component.front()];
  Vec3 high = low;
  for (const std::uint32_t v : component) {
    low = glm::min(low, rest[v]);
    high = glm::max(high, rest[v]);
  }
  const Vec3 middle = 0.5 * (low + high);
  const std::uint32_t outermost[1] = {farthestVertex(rest, component, [&](std::uint32_t v) { return glm::length(rest[v] - middle); })};
  const std::vector<double> distance = edgeDistance(mesh, outermost);
  return farthestVertex(rest, component, [&](std::uint32_t v) { return distance[v]; });
}

// The kept contour at the centre of the tree: the smallest largest path distance (through ring
// centroids) to any region of the tree. In a tree that is the larger of the distances to the two
// ends of a longest path.
std::int32_t centreContour(const LevelGraph& graph, const LevelTree& tree) {
  const std::size_t r_count = graph.regions.size();
  const std::size_t c_count = graph.contours.size();
  // A graph over regions and kept contours: node r for a region, r_count + c for a contour.
  auto distancesFrom = [&](std::size_t start) {
    std::vector<double> d(r_count + c_count, -1.0);
    std::vector<std::size_t> stack{start};
    d[start] = 0.0;
    auto position = [&](std::size_t n) { return n < r_count ? graph.regions[n].centroid : graph.contours[n - r_count].centroid; };
    while (!stack.empty()) {
      const std::size_t n = stack.back();
      stack.pop_back();
      auto visit = [&](std::size_t m) {
        if (d[m] >= 0.0) return;
        d[m] = d[n] + glm::length(position(m) - position(n));
        stack.push_back(m);
      };
      if (n < r_count) {
        for (const std::uint32_t c : graph.regions[n].contours) {
          if (tree.kept(c)) visit(r_count + c);
        }
      } else {
        const std::uint32_t c = static_cast<std::uint32_t>(n - r_count);
        visit(graph.contours[c].lower);
        visit(graph.contours[c].upper);
      }
    }
    return d;
  };
  const std::vector<double> from_root = distancesFrom(tree.root);
  const auto end_a = static_cast<std::size_t>(std::max_element(from_root.begin(), from_root.end()) - from_root.begin());
  const std::vector<double> from_a = distancesFrom(end_a);
  const auto end_b = static_cast<std::size_t>(std::max_element(from_a.begin(), from_a.end()) - from_a.begin());
  const std::vector<double> from_b = distancesFrom(end_b);
  std::int32_t best = -1;
  double best_eccentricity = std::numeric_limits<double>::infinity();
  for (std::uint32_t c = 0; c < c_count; ++c) {
    if (!tree.kept(c) || !graph.contours[c].closed) continue;
    const double e = std::max(from_a[r_count + c], from_b[r_count + c]);
    if (e < best_eccentricity) {
      best_eccentricity = e;
      best = static_cast<std::int32_t>(c);
    }
  }
  return best;
}

// The vertices within `half_width` (a mean edge length at least, so that the band is a closed
// ring of vertices even where edges run along it) of the plane through the centre ring's centroid, across the
// chain of ring centroids there (three rings either way) and within two ring radii of it: of the
// pieces that leaves (a limb may pass near), the one holding most of the centre ring's own edge
// ends, with their distances to the plane (so the distance grown from them starts flat). The
// ring's own vertices (distances left empty: 0) if that leaves none.
std::vector<std::uint32_t> centreBand(std::span<const Vec3> rest, const MeshTopology& mesh, const LevelGraph& graph,
                                      const LevelTree& tree, std::uint32_t centre, double half_width,
                                      std::vector<double>& distance_to_plane) {
  constexpr int kSteps = 3;
  const LevelContour& ring = graph.contours[centre];
  Vec3 toward_root = ring.centroid;
  Vec3 away = ring.centroid;
  double radius = ring.radius;
  std::uint32_t c = centre;
  for (int k = 0; k < kSteps; ++k) {
    const std::uint32_t r = tree.parentRegion(graph, c);
    if (tree.parent_contour[r] < 0 || tree.children[r].size() != 1) break;
    c = static_cast<std::uint32_t>(tree.parent_contour[r]);
    toward_root = graph.contours[c].centroid;
    radius = std::max(radius, graph.contours[c].radius);
  }
  c = centre;
  for (int k = 0; k < kSteps; ++k) {
    const auto r = static_cast<std::uint32_t>(tree.child_region[c]);
    if (tree.children[r].size() != 1) break;
    c = tree.children[r].front();
    away = graph.contours[c].centroid;
    radius = std::max(radius, graph.contours[c].radius);
  }
  std::vector<std::uint32_t> ring_vertices;
  for (const CurvePoint& p : ring.points) ring_vertices.push_back(p.a);
  std::sort(ring_vertices.begin(), ring_vertices.end());
  ring_vertices.erase(std::unique(ring_vertices.begin(), ring_vertices.end()), ring_vertices.end());
  distance_to_plane.clear();
  if (!(glm::length(away - toward_root) > 0.0)) return ring_vertices;
  const Vec3 normal = glm::normalize(away - toward_root);
  std::vector<std::int32_t> label(rest.size(), -1);  // -2: in the band, not yet labelled
  std::vector<std::uint32_t> band;
  for (std::uint32_t v = 0; v < rest.size(); ++v) {
    const Vec3 d = rest[v] - ring.centroid;
    if (std::abs(glm::dot(normal, d)) <= half_width && glm::length(d) <= 2.0 * radius) {
      label[v] = -2;
      band.push_back(v);
    }
  }
  // Pieces of the band along mesh edges; the one with most of the ring's vertices wins.
  std::vector<std::size_t> votes;
  std::vector<std::uint32_t> stack;
  for (const std::uint32_t s : band) {
    if (label[s] != -2) continue;
    const auto piece = static_cast<std::int32_t>(votes.size());
    votes.push_back(0);
    label[s] = piece;
    stack.push_back(s);
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      for (std::uint32_t k = mesh.vertex_offsets[u]; k < mesh.vertex_offsets[u + 1]; ++k) {
        const std::uint32_t w = mesh.vertex_neighbours[k];
        if (label[w] == -2) {
          label[w] = piece;
          stack.push_back(w);
        }
      }
    }
  }
  for (const std::uint32_t v : ring_vertices) {
    for (std::uint32_t k = mesh.vertex_offsets[v]; k < mesh.vertex_offsets[v + 1]; ++k) {
      const auto& e = mesh.edges[mesh.vertex_edges[k]];
      for (const std::uint32_t w : e) {
        if (label[w] >= 0) ++votes[static_cast<std::size_t>(label[w])];
      }
    }
  }
  if (votes.empty()) return ring_vertices;
  const auto best = static_cast<std::int32_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
  if (votes[static_cast<std::size_t>(best)] == 0) return ring_vertices;
  std::vector<std::uint32_t> chosen;
  for (const std::uint32_t v : band) {
    if (label[v] != best) continue;
    chosen.push_back(v);
    distance_to_plane.push_back(std::abs(glm::dot(normal, rest[v] - ring.centroid)));
  }
  return chosen;
}

CurveSkeleton skeletonFromLevels(std::span<const Vec3> rest, const LevelGraph& graph, const LevelTree& tree,
                                 const TreeParts& parts, const MeshTopology& mesh, std::span<const SkeletonAnchor> root_anchors,
                                 std::vector<IsoCurve>& curves) {
  CurveSkeleton s;
  std::vector<std::int32_t> region_node(graph.regions.size(), -1);
  std::vector<std::int32_t> contour_node(graph.contours.size(), -1);
  // The regions in the order their nodes are made (breadth first from the root), so that every
  // node's anchors can be counted first and go into one array sized once: the array holds the
  // points of every curve, and a reallocation would copy them all.
  std::vector<std::uint32_t> order{tree.root};
  std::vector<std::vector<SkeletonAnchor>> region_anchors(graph.regions.size());
  std::size_t anchor_count = root_anchors.size();
  for (std::size_t head = 0; head < order.size(); ++head) {
    for (const std::uint32_t c : tree.children[order[head]]) {
      if (graph.contours[c].closed) anchor_count += graph.contours[c].points.size();
      const auto q = static_cast<std::uint32_t>(tree.child_region[c]);
      bool has_node = false;
      const SkeletonNodeKind kind = regionKind(tree, q, &has_node);
      if (has_node && !graph.regions[q].vertices.empty()) {
        region_anchors[q] = kind == SkeletonNodeKind::kTip ? tipAnchors(graph, q, mesh) : regionAnchors(graph, q);
        anchor_count += region_anchors[q].size();
      }
      order.push_back(q);
    }
  }
  s.anchors.reserve(anchor_count);
  addSkeletonNode(s, SkeletonNodeKind::kRoot, -1, static_cast<std::uint32_t>(parts.region_part[tree.root]),
                  tree.ringRadius(graph, tree.root, 0.0), root_anchors, rest);
  region_node[tree.root] = 0;
  for (const std::uint32_t r : order) {
    const std::int32_t from = region_node[r] >= 0 ? region_node[r] : contour_node[static_cast<std::size_t>(tree.parent_contour[r])];
    for (const std::uint32_t c : tree.children[r]) {
      const LevelContour& contour = graph.contours[c];
      const auto part = static_cast<std::uint32_t>(parts.contour_part[c]);
      IsoCurve curve = orderedContour(contour, part);
      if (contour.closed) {
        contour_node[c] = static_cast<std::int32_t>(s.nodeCount());
        addCurveNode(s, SkeletonNodeKind::kCurve, from, part, contour.radius, curve.points, curve.closed, rest);
      } else {
        contour_node[c] = from;  // an arc cut off by a hole or rim: its centroid is off the axis
      }
      curves.push_back(std::move(curve));
      const auto q = static_cast<std::uint32_t>(tree.child_region[c]);
      bool has_node = false;
      const SkeletonNodeKind kind = regionKind(tree, q, &has_node);
      if (has_node && !graph.regions[q].vertices.empty()) {
        region_node[q] = static_cast<std::int32_t>(s.nodeCount());
        const double radius = kind == SkeletonNodeKind::kTip ? 0.5 * contour.radius : tree.ringRadius(graph, q, 0.0);
        addSkeletonNode(s, kind, contour_node[c], part, radius, region_anchors[q], rest);
      }
    }
  }
  return s;
}

// The band vertex nearest its plane (ties by position): the second pass's tree hangs from its
// region, which must not depend on the vertex order.
std::uint32_t bandRoot(std::span<const Vec3> rest, std::span<const std::uint32_t> band,
                       std::span<const double> distance_to_plane) {
  std::uint32_t root = band.front();
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < band.size(); ++k) {
    const double d = distance_to_plane.empty() ? 0.0 : distance_to_plane[k];
    if (d < nearest || (d == nearest && positionBefore(rest[band[k]], rest[root]))) {
      nearest = d;
      root = band[k];
    }
  }
  return root;
}

}  // namespace

CurveSource resolveCurveSource(CurveSource source, const FaceList& faces) {
  if (source != CurveSource::kAuto) return source;
  return quadFraction(faces) >= kQuadDominant ? CurveSource::kEdgeLoops : CurveSource::kLevels;
}

std::vector<Vec3> curveSkeletonPositions(const CurveSkeleton& skeleton, std::span<const Vec3> pose) {
  std::vector<Vec3> out(skeleton.nodeCount(), Vec3(0.0));
  for (std::size_t n = 0; n < skeleton.nodeCount(); ++n) {
    double total = 0.0;
    for (std::uint32_t k = skeleton.anchor_offsets[n]; k < skeleton.anchor_offsets[n + 1]; ++k) {
      const SkeletonAnchor& a = skeleton.anchors[k];
      out[n] += a.weight * curvePointPosition(pose, a.point);
      total += a.weight;
    }
    if (total > 0.0) out[n] /= total;
  }
  return out;
}

Result<CurveSkeletonResult> buildCurveSkeleton(std::span<const Vec3> rest, const FaceList& faces,
                                               const CurveSkeletonOptions& options) {
  ODESKIN_ASSIGN_OR_RETURN(const PositionBox box, checkInput(rest, faces, options));
  const Clock::time_point topology_start = Clock::now();
  const MeshTopology mesh = meshTopology(rest, faces);
  double edge_sum = 0.0;
  for (const double l : mesh.edge_lengths) edge_sum += l;
  const double mean_edge = mesh.edges.empty() ? 0.0 : edge_sum / static_cast<double>(mesh.edges.size());
  if (!(mean_edge > 0.0)) return degenerate("curve skeleton: every edge of the mesh has length 0");
  const double seconds_topology = secondsSince(topology_start);
  const Clock::time_point start = Clock::now();
  const double spacing = options.level_spacing > 0.0
                             ? options.level_spacing
                             : std::min(kDefaultSpacingEdges * mean_edge, box.diagonal / kMinLevelsPerDiagonal);
  const PruneRule prune{options.prune_radii, options.prune_fraction * box.diagonal, options.prune_thin_fraction * box.diagonal};

  // The band the second pass starts from: across the body at its centre, so that rings run
  // across the body on both sides of it. The shortest section through the body's centre where
  // there is one; else, from a first, coarse pass (edge paths from an extremity, levels
  // kFirstPassSpacing apart), a band across its level tree's centre ring.
  const std::vector<std::uint32_t> component = largestComponent(mesh);
  std::vector<char> in_component(rest.size(), 0);
  for (const std::uint32_t v : component) in_component[v] = 1;
  std::vector<std::uint32_t> band;
  std::vector<double> band_distance;
  bool band_from_first_pass = false;
  Clock::time_point coarse_start = start;
  if (std::optional<GirthPlane> plane = bodySection(rest, mesh, component, in_component)) {
    band = std::move(plane->vertices);
    band_distance = std::move(plane->distances);
  }
  const double seconds_centre = secondsSince(start);
  double seconds_edge_distance = 0.0;
  if (band.empty()) {
    band_from_first_pass = true;
    const Clock::time_point first_start = Clock::now();
    const std::uint32_t extremity[1] = {componentExtremity(rest, mesh, component)};
    const std::vector<double> f1 = edgeDistance(mesh, extremity);
    coarse_start = Clock::now();
    seconds_edge_distance = std::chrono::duration<double>(coarse_start - first_start).count();
    const LevelGraph first = levelGraph(rest, mesh, f1, kFirstPassSpacing * spacing);
    const LevelTree first_tree = levelTree(first, first.vertex_region[extremity[0]], prune);
    const std::int32_t centre = centreContour(first, first_tree);
    if (centre < 0) {
      return degenerate("curve skeleton: no closed ring at level spacing " + messageNumber(kFirstPassSpacing * spacing) +
                        " (the mesh is too small or too flat for levels)");
    }
    band = centreBand(rest, mesh, first, first_tree, static_cast<std::uint32_t>(centre), std::max(0.5 * spacing, mean_edge),
                      band_distance);
  }
  const Clock::time_point marching_start = Clock::now();
  const std::vector<double> f = surfaceDistance(mesh, rest, band, band_distance);
  const Clock::time_point fine_start = Clock::now();
  const LevelGraph graph = levelGraph(rest, mesh, f, spacing);
  const LevelTree tree = levelTree(graph, graph.vertex_region[bandRoot(rest, band, band_distance)], prune);
  const TreeParts parts = treeParts(graph, tree);
  // The root node is the centre of the band itself (the slab next to it may hold part of a ring).
  std::vector<SkeletonAnchor> root_anchors;
  root_anchors.reserve(band.size());
  for (const std::uint32_t v : band) root_anchors.push_back({CurvePoint{v, v, 0.0}, 1.0});

  CurveSkeletonResult result;
  result.seconds_topology = seconds_topology;
  result.seconds_centre = seconds_centre;
  result.seconds_edge_distance = seconds_edge_distance;
  result.seconds_coarse_levels = band_from_first_pass ? std::chrono::duration<double>(marching_start - coarse_start).count() : 0.0;
  result.seconds_marching = std::chrono::duration<double>(fine_start - marching_start).count();
  result.seconds_fine_levels = secondsSince(fine_start);
  result.vertex_parts = parts.vertex_parts;
  result.part_count = parts.parts.size();
  result.pruned_branches = tree.pruned_branches;
  for (const double d : f) result.unreached_vertices += std::isfinite(d) ? 0 : 1;
  result.source = resolveCurveSource(options.source, faces);
  if (result.source == CurveSource::kEdgeLoops) {
    const double levels = secondsSince(start);
    const Clock::time_point loops_start = Clock::now();
    EdgeLoopStats stats;
    Result<CurveSkeleton> from_loops = skeletonFromEdgeLoops(rest, faces, graph, tree, parts, f, mesh, root_anchors, result.curves, stats);
    result.axial_edges = stats.axial_edges;
    result.circumferential_edges = stats.circumferential_edges;
    result.unknown_edges = stats.unknown_edges;
    result.edge_loop_rings = stats.rings;
    result.seconds_edge_loops = stats.seconds_loops;
    result.axial_lines = stats.axial_lines;
    if (from_loops.ok()) {
      result.skeleton = std::move(*from_loops);
      result.seconds_curves = levels + stats.seconds_loops;
      result.seconds_skeleton = secondsSince(loops_start) - stats.seconds_loops;
      return result;
    }
    result.source = CurveSource::kLevels;
    result.note = "quad edge loops failed (" + from_loops.status().message() + "); the geodesic rings are the curves";
    result.curves.clear();
  }
  if (result.source == CurveSource::kPlaneCuts) {
    const double levels = secondsSince(start);
    const Clock::time_point cuts = Clock::now();
    double seconds_cuts = 0.0;
    Result<CurveSkeleton> from_cuts = skeletonFromPlaneCuts(rest, faces, graph, tree, parts, f, mesh, root_anchors, result.curves, seconds_cuts);
    if (from_cuts.ok()) {
      result.skeleton = std::move(*from_cuts);
      result.seconds_curves = levels + seconds_cuts;
      result.seconds_skeleton = secondsSince(cuts) - seconds_cuts;
      return result;
    }
    result.source = CurveSource::kLevels;
    result.note = "plane cuts failed (" + from_cuts.status().message() + "); the geodesic rings are the curves";
    result.curves.clear();
  }
  result.seconds_curves = secondsSince(start);
  const Clock::time_point skeleton_start = Clock::now();
  result.skeleton = skeletonFromLevels(rest, graph, tree, parts, mesh, root_anchors, result.curves);
  result.seconds_skeleton = secondsSince(skeleton_start);
  return result;
}

}  // namespace odeskin
