// SPDX-License-Identifier: MIT
// Poses of the mesh a curve network was extracted from: is vertex i the same surface point as in
// the reference, and what to read where it is not.
// A pose file can number some vertices differently from the reference while keeping its face list
// (face-poses: face-01 and face-03..09 renumber about 410 vertices around the mouth; their
// triangles then span up to 1.5 units, docs/results.md). Such a vertex's edges stretch far more than
// any expression stretches skin: flagVertices marks both ends of every edge whose length grows by
// more than `ratio` times its reference length. The curve network must not read flagged vertices:
// fillFlagged gives them the reference position plus a displacement interpolated from their
// unflagged neighbours (a harmonic function on the mesh graph), so the samples near them follow the
// expression around them. The deviation figures leave flagged vertices out (measureDeviation's
// `excluded`), and say how many.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

struct PoseFlags {
  std::vector<std::uint8_t> flagged;  // per vertex: 1 where an edge stretched by more than the ratio
  std::size_t flagged_vertices = 0;
  std::size_t stretched_edges = 0;
  double max_stretch = 0.0;           // the largest edge length ratio pose / reference
};

// kInvalidArgument for different vertex counts, a face index out of range, positions not finite or
// too large or small for edge lengths ("the reference: ..." or "the pose: ...", checkedPositionBox), or
// ratio <= 1 or NaN.
// Edges of zero reference length count as stretched if they have any length in the pose.
Result<PoseFlags> flagVertices(std::span<const Vec3> reference, std::span<const Vec3> pose, const FaceList& faces,
                               double ratio);

// The pose with every flagged vertex moved to reference + d, where d is the mean of its neighbours'
// d (unflagged vertices keep d = pose - reference). kInvalidArgument when a connected group of
// flagged vertices has no unflagged neighbour (nothing to interpolate from), or sizes differ.
Result<std::vector<Vec3>> fillFlagged(std::span<const Vec3> reference, std::span<const Vec3> pose, const FaceList& faces,
                                      std::span<const std::uint8_t> flagged);

}  // namespace odeskin
