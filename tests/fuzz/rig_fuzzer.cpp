// SPDX-License-Identifier: MIT
// libFuzzer target: the rig from iso-parametric curves (engine/rig/curve_rig.hpp) on any mesh the
// OBJ reader accepts, as `odeskin rig` builds it: the curve skeleton from the geodesic rings (with
// distance weights), from plane cuts and from quad edge loops, then the animation skeleton. The
// rig's contract is looser than a reader's: the curve skeleton asks only for valid faces, so a
// non-manifold, degenerate or disconnected mesh must give a rig or a Status, never a crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/obj_reader.hpp"
#include "engine/rig/curve_rig.hpp"
#include "fuzz_checks.hpp"

namespace {

using namespace odeskin;

// The plane cuts cost more than linear time per mesh; larger meshes add no new shapes of input.
constexpr std::size_t kMaxVertices = 4000;

void checkCurvePoint(const CurvePoint& p, std::size_t vertices, const std::string& where) {
  fuzz::require(p.a < vertices && p.b < vertices, where + ": a curve point off the mesh");
  fuzz::require(p.t >= 0.0 && p.t <= 1.0, where + ": a curve point off its edge");
}

void checkRig(const CurveRig& r, std::size_t vertices, bool weights) {
  const CurveSkeleton& s = r.curve_skeleton.skeleton;
  const std::size_t nodes = s.nodeCount();
  fuzz::require(nodes > 0 && s.radii.size() == nodes && s.kinds.size() == nodes && s.parents.size() == nodes &&
                    s.parts.size() == nodes && s.anchor_offsets.size() == nodes + 1,
                "curve skeleton arrays of different lengths");
  fuzz::require(s.parents[0] == -1, "curve skeleton: node 0 has a parent");
  for (std::size_t n = 0; n < nodes; ++n) {
    fuzz::require(n == 0 || (s.parents[n] >= 0 && static_cast<std::size_t>(s.parents[n]) < n),
                  "curve skeleton: a parent does not precede its child");
    fuzz::require(s.anchor_offsets[n] <= s.anchor_offsets[n + 1], "curve skeleton: anchor offsets go down");
    fuzz::require(fuzz::finite(s.positions[n]), "curve skeleton: a node is not finite");
  }
  fuzz::require(s.anchor_offsets.front() == 0 && s.anchor_offsets.back() == s.anchors.size(),
                "curve skeleton: anchor offsets do not span the anchors");
  for (const SkeletonAnchor& a : s.anchors) checkCurvePoint(a.point, vertices, "anchor");
  for (const IsoCurve& curve : r.curve_skeleton.curves) {
    for (const CurvePoint& p : curve.points) checkCurvePoint(p, vertices, "curve");
  }
  fuzz::require(r.curve_skeleton.vertex_parts.size() == vertices, "curve skeleton: vertex parts of the wrong size");
  const Skeleton& bones = r.rig.skeleton;
  fuzz::require(bones.boneCount() > 0 && bones.parents.size() == bones.boneCount(), "rig without bones");
  for (std::size_t b = 0; b < bones.boneCount(); ++b) {
    fuzz::require(bones.parents[b] >= -1 && bones.parents[b] < static_cast<std::int64_t>(b),
                  "rig: a bone's parent does not precede it");
  }
  if (weights) {
    fuzz::require(validateInfluences(r.rig.influences, vertices, static_cast<std::uint32_t>(bones.boneCount())).ok(),
                  "rig: invalid weights");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Result<ObjMesh> mesh = parseObj(fuzz::text(data, size), "fuzz.obj");
  if (!mesh.ok() || mesh->positions.size() > kMaxVertices) return 0;
  for (const CurveSource source : {CurveSource::kLevels, CurveSource::kPlaneCuts, CurveSource::kEdgeLoops}) {
    CurveRigOptions options;
    options.curves.source = source;
    options.compute_weights = source == CurveSource::kLevels;
    const Result<CurveRig> rig = buildCurveRig(mesh->positions, mesh->faces, {}, options);
    if (!rig.ok()) {
      fuzz::require(rig.status().code() != StatusCode::kInternal, "a mesh refused as an internal error: " + rig.status().toString());
      continue;
    }
    checkRig(*rig, mesh->positions.size(), options.compute_weights);
  }
  return 0;
}
