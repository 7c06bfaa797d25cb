// SPDX-License-Identifier: MIT
// buildIsoCurves (thesis 6.3.1 and 5.3): parts and seams, then the curves of each part (plane
// cuts, or quad edge loops), one parametrisation for neighbouring curves, and every vertex bound.
#include "iso_curves.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/parallel.hpp"
#include "../core/position_box.hpp"
#include "../mesh/adjacency.hpp"
#include "../mesh/face_fans.hpp"
#include "../mesh/poly_mesh.hpp"
#include "curve_orientation.hpp"
#include "edge_loops.hpp"
#include "part_planes.hpp"
#include "part_segmentation.hpp"
#include "plane_cuts.hpp"
#include "vertex_binding.hpp"

namespace odeskin {
namespace {

// Default spacing between cuts in mean edge lengths (a limb gets a curve every ~3 edge rings).
constexpr double kDefaultSpacingEdges = 3.0;
// kAuto takes edge loops when at least this fraction of the faces are quads.
constexpr double kQuadDominant = 0.8;

Status checkInput(std::span<const Vec3> rest, const FaceList& faces, const Skeleton& skeleton,
                  const Influences& influences, const CurveOptions& options) {
  const std::size_t count = rest.size();
  if (count == 0) return invalidArgument("iso-curves: the mesh has no vertices");
  ODESKIN_TRY(checkedPositionBox(rest, "iso-curves").status());
  const std::size_t bones = skeleton.boneCount();
  if (bones == 0) return invalidArgument("iso-curves: the skeleton has no bones");
  if (skeleton.tails.size() != bones) {
    return invalidArgument("iso-curves: the skeleton has " + std::to_string(bones) + " heads but " +
                           std::to_string(skeleton.tails.size()) + " tails");
  }
  for (std::size_t b = 0; b < bones; ++b) {
    if (!isFinite(skeleton.heads[b]) || !isFinite(skeleton.tails[b])) {
      return invalidArgument("iso-curves: bone " + std::to_string(b) + " has a non-finite joint");
    }
  }
  if (influences.vertexCount() != count) {
    return invalidArgument("iso-curves: influences for " + std::to_string(influences.vertexCount()) + " vertices, mesh has " +
                           std::to_string(count));
  }
  ODESKIN_TRY(validateInfluences(influences, count, static_cast<std::uint32_t>(bones)));
  if (faces.face_offsets.empty() || faces.face_offsets.front() != 0 || faces.face_offsets.back() != faces.indices.size() ||
      !std::is_sorted(faces.face_offsets.begin(), faces.face_offsets.end())) {
    return invalidArgument("iso-curves: face offsets are not a compressed row layout of the face indices");
  }
  if (!(options.spacing >= 0.0) || !std::isfinite(options.spacing)) {
    return invalidArgument("iso-curves: spacing must be a finite number >= 0 (0: automatic)");
  }
  if (!(options.snap_threshold >= 0.0 && options.snap_threshold < 0.5)) {
    return invalidArgument("iso-curves: snap threshold must be in [0, 0.5)");
  }
  if (options.min_points < 3) return invalidArgument("iso-curves: min_points must be at least 3");
  return okStatus();
}

}  // namespace

Result<CurveSet> buildIsoCurves(std::span<const Vec3> rest, const FaceList& faces, const Skeleton& skeleton,
                                const Influences& influences, const CurveOptions& options) {
  ODESKIN_TRY(checkInput(rest, faces, skeleton, influences, options));
  if (faces.faceCount() == 0) return degenerate("iso-curves: the mesh has no faces to cut");
  // OpenMesh's half-edge mesh costs more than the rest of the work with it: a plainly manifold mesh
  // (which OpenMesh accepts) skips it unless its quads are walked; any other gets OpenMesh's verdict.
  std::optional<PolyMesh> mesh;
  auto polyMesh = [&]() -> Status {
    if (mesh) return okStatus();
    ODESKIN_ASSIGN_OR_RETURN(PolyMesh built, buildPolyMesh(rest, faces, "iso-curves"));
    mesh = std::move(built);
    return okStatus();
  };
  // Indices in range before anything indexes with them (buildPolyMesh names the face otherwise).
  if (!std::all_of(faces.indices.begin(), faces.indices.end(), [&](std::uint32_t i) { return i < rest.size(); })) {
    ODESKIN_TRY(polyMesh());
  }
  const auto min_points = static_cast<std::size_t>(options.min_points);
  const bool loops = options.method == CurveMethod::kEdgeLoops ||
                     (options.method == CurveMethod::kAuto && quadFraction(faces) >= kQuadDominant);
  // The manifold check, the adjacency and the parts it gives, and the cut mesh need one another
  // only later: they are made at once.
  std::optional<std::vector<std::vector<std::uint32_t>>> simple_loops;
  VertexAdjacency adjacency;
  double mean_edge = 0.0;
  Segmentation seg;
  CutMesh cut_mesh;
  parallelInvoke([&] { simple_loops = simpleManifoldBoundaryLoops(faces, rest.size()); },
                 [&] {
                   adjacency = vertexAdjacency(faces, rest.size());
                   mean_edge = meanEdgeLength(rest, adjacency);
                   // Patches smaller than two curves' worth of points cannot carry a curve of their own.
                   seg = segmentParts(rest, adjacency, skeleton, influences, 2 * min_points,
                                      std::max<std::size_t>(3, min_points / 2));
                 },
                 [&] {
                   if (!loops) cut_mesh = buildCutMesh(faces, rest.size());
                 });
  if (!simple_loops) ODESKIN_TRY(polyMesh());
  if (!(mean_edge > 0.0)) return degenerate("iso-curves: every edge of the mesh has length 0");
  const double spacing = options.spacing > 0.0 ? options.spacing : kDefaultSpacingEdges * mean_edge;

  CurveLayout layout;
  if (loops) {
    ODESKIN_TRY(polyMesh());
    layout = edgeLoopCurves(rest, *mesh, seg, min_points);
  }
  if (!loops || (options.method == CurveMethod::kAuto && layout.curves.empty())) {
    if (loops) cut_mesh = buildCutMesh(faces, rest.size());
    layout = planeCutCurves(rest, cut_mesh, adjacency, seg, {spacing, options.snap_threshold, min_points});
    addBoundaryLoops(rest, simple_loops ? *simple_loops : boundaryLoops(*mesh), seg, spacing, min_points, layout);
  }
  orientCurves(rest, seg, layout);
  compactCurves(layout);
  if (layout.curves.empty()) {
    return degenerate(std::string("iso-curves: no ") + (loops ? "edge loop" : "plane cut") + " gives a curve of " +
                      std::to_string(min_points) + " points or more (spacing " + messageNumber(spacing) + ")");
  }

  CurveSet set;
  set.bindings = bindVertices(rest, adjacency, seg, layout, spacing);
  set.curves.reserve(layout.curves.size());
  for (CurveDraft& draft : layout.curves) {
    IsoCurve curve;
    curve.points = std::move(draft.points);
    curve.v = std::move(draft.v);
    curve.closed = draft.closed;
    curve.part = draft.bone;
    set.curves.push_back(std::move(curve));
  }
  set.vertex_parts.resize(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) set.vertex_parts[i] = seg.parts[seg.vertex_part[i]].bone;
  const Status valid = validateCurveSet(set, rest.size());
  if (!valid.ok()) return internalError("iso-curves: built an invalid curve set: " + valid.message());
  return set;
}

}  // namespace odeskin
