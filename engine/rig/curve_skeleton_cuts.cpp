// SPDX-License-Identifier: MIT
// The curve skeleton from odeskin's own curve identification (curves/iso_curves.hpp): the parts of
// the level tree become a pseudo-rig (one bone per part, from its start region to its end region,
// every vertex weighted 1 to its part), which buildIsoCurves cuts into curves across each part.
// Within a part the curves are ordered by the geodesic distance of their points, so the chain runs
// from the part's start (the root or a junction) to its end. A seam curve, shared by two parts,
// is put on the deeper one: it is where the limb leaves the body, the first node of that limb.
#include <algorithm>
#include <chrono>
#include <numeric>

#include <glm/geometric.hpp>

#include "../curves/iso_curves.hpp"
#include "curve_skeleton_parts.hpp"

namespace odeskin {

Result<CurveSkeleton> skeletonFromPlaneCuts(std::span<const Vec3> rest, const FaceList& faces, const LevelGraph& graph,
                                            const LevelTree& tree, const TreeParts& parts, std::span<const double> f,
                                            const MeshTopology& mesh, std::span<const SkeletonAnchor> root_anchors,
                                            std::vector<IsoCurve>& curves, double& seconds_cuts) {
  const auto cut_start = std::chrono::steady_clock::now();
  const std::size_t p_count = parts.parts.size();
  Skeleton pseudo;
  pseudo.names.resize(p_count);
  for (std::size_t p = 0; p < p_count; ++p) {
    const TreePart& part = parts.parts[p];
    pseudo.names[p] = "part" + std::to_string(p);
    pseudo.parents.push_back(part.parent);
    pseudo.heads.push_back(graph.regions[part.start_region].centroid);
    pseudo.tails.push_back(part.end_region >= 0 ? graph.regions[static_cast<std::size_t>(part.end_region)].centroid
                                                : pseudo.heads.back());
  }
  Influences hard;
  hard.offsets.resize(rest.size() + 1);
  std::iota(hard.offsets.begin(), hard.offsets.end(), 0u);
  hard.bones = parts.vertex_parts;
  hard.weights.assign(rest.size(), 1.0);
  Result<CurveSet> set = buildIsoCurves(rest, faces, pseudo, hard);
  if (!set.ok() && set.status().code() == StatusCode::kDegenerate) {
    CurveOptions short_curves;  // low-poly meshes: accept short curves, as the fit pipeline does
    short_curves.min_points = 3;
    set = buildIsoCurves(rest, faces, pseudo, hard, short_curves);
  }
  if (!set.ok()) return set.status();
  seconds_cuts = std::chrono::duration<double>(std::chrono::steady_clock::now() - cut_start).count();

  return skeletonFromPartCurves(rest, graph, tree, parts, f, mesh, root_anchors, set->curves, curves);
}

CurveSkeleton skeletonFromPartCurves(std::span<const Vec3> rest, const LevelGraph& graph, const LevelTree& tree,
                                     const TreeParts& parts, std::span<const double> f, const MeshTopology& mesh,
                                     std::span<const SkeletonAnchor> root_anchors, std::vector<IsoCurve>& found,
                                     std::vector<IsoCurve>& curves) {
  const std::size_t p_count = parts.parts.size();
  // Each curve on one part (the deepest it touches), keyed by the mean distance of its points.
  std::vector<std::vector<std::pair<double, std::uint32_t>>> per_part(p_count);
  for (std::uint32_t c = 0; c < found.size(); ++c) {
    const IsoCurve& curve = found[c];
    std::uint32_t part = curve.part < p_count ? curve.part : 0;
    double key = 0.0;
    for (const CurvePoint& p : curve.points) {
      for (const std::uint32_t v : {p.a, p.b}) {
        const std::uint32_t q = parts.vertex_parts[v];
        if (parts.parts[q].depth > parts.parts[part].depth) part = q;
      }
      key += (1.0 - p.t) * f[p.a] + p.t * f[p.b];
    }
    per_part[part].push_back({key / static_cast<double>(std::max<std::size_t>(1, curve.points.size())), c});
  }

  CurveSkeleton s;
  std::vector<std::int32_t> region_node(graph.regions.size(), -1);
  addSkeletonNode(s, SkeletonNodeKind::kRoot, -1, 0, tree.ringRadius(graph, tree.root, 0.0), root_anchors, rest);
  region_node[tree.root] = 0;
  for (std::uint32_t p = 0; p < p_count; ++p) {
    const TreePart& part = parts.parts[p];
    std::int32_t previous = region_node[part.start_region];
    if (previous < 0) previous = 0;  // a start region without vertices: hang the part on the root
    std::sort(per_part[p].begin(), per_part[p].end());
    double last_radius = s.radii[static_cast<std::size_t>(previous)];
    for (const auto& [key, c] : per_part[p]) {
      IsoCurve& curve = found[c];
      curve.part = p;
      if (!curve.closed) {  // an arc cut off by a hole or rim: its centroid is off the axis
        curves.push_back(curve);
        continue;
      }
      const std::int32_t node = static_cast<std::int32_t>(s.nodeCount());
      addCurveNode(s, SkeletonNodeKind::kCurve, previous, p, 0.0, curve.points, curve.closed, rest);
      double radius = 0.0;
      for (const CurvePoint& q : curve.points) radius += glm::length(curvePointPosition(rest, q) - s.positions.back());
      s.radii.back() = last_radius = radius / static_cast<double>(std::max<std::size_t>(1, curve.points.size()));
      previous = node;
      curves.push_back(curve);
    }
    if (part.end_region < 0) continue;
    const auto end = static_cast<std::uint32_t>(part.end_region);
    bool has_node = false;
    const SkeletonNodeKind kind = regionKind(tree, end, &has_node);
    if (!has_node || graph.regions[end].vertices.empty()) continue;
    region_node[end] = static_cast<std::int32_t>(s.nodeCount());
    const double radius = kind == SkeletonNodeKind::kTip ? 0.5 * last_radius : tree.ringRadius(graph, end, last_radius);
    addSkeletonNode(s, kind, previous, p, radius,
                    kind == SkeletonNodeKind::kTip ? tipAnchors(graph, end, mesh) : regionAnchors(graph, end), rest);
  }
  return s;
}

}  // namespace odeskin
