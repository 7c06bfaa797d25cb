// SPDX-License-Identifier: MIT
// Distance weights in the spirit of Yang & Zhang (2006), "Automatic skin weighting by inverse
// distance to bones":
//  1. d_ib = distance from rest vertex i to bone b's segment [head, tail] (a point when tail ==
//     head), floored at 1e-6 of the mesh's longest box side so a vertex on a bone stays finite.
//  2. Nearest-bones rule instead of their visibility test: vertex i may only take weight from its
//     nearest bone n(i) and the bones joined to n(i) (its parent, its children, and bones sharing
//     one of its joint positions). Bone segments that are close in space but far apart in the
//     skeleton (one leg and the other, an arm and the torso beside it) then never share a vertex,
//     while bones meeting at a joint blend across it. It needs no ray casting, and it agrees with
//     visibility wherever the nearest bone is the one inside the vertex's limb.
//  3. w_ib = d_ib^-p over those bones, normalised (p = falloff_power; larger p, sharper joints).
//  4. smoothing_iterations steps of umbrella smoothing over the vertex graph (lambda = 1/2) remove
//     the creases where n(i) switches; each step is a convex mix of rows, so rows stay >= 0 and
//     keep summing to 1.
//  5. The max_influences largest weights are kept and renormalised to sum to 1.
#include "distance_weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>


#include "../core/number_text.hpp"
#include "../core/parallel.hpp"
#include "../core/position_box.hpp"
#include "../mesh/adjacency.hpp"
#include "weight_rows.hpp"

namespace odeskin {
namespace {

constexpr double kDistanceFloor = 1e-6;  // x longest box side
constexpr double kJointTolerance = 1e-9; // x longest box side: joints this close are one joint
constexpr double kSmoothingLambda = 0.5;

double segmentDistance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 s = b - a;
  const double length2 = glm::dot(s, s);
  const double t = length2 > 0.0 ? std::clamp(glm::dot(x - a, s) / length2, 0.0, 1.0) : 0.0;
  return glm::length(x - (a + t * s));
}

// For each bone, itself and the bones joined to it.
std::vector<std::vector<std::uint32_t>> joinedBones(const Skeleton& s, double tolerance) {
  const std::size_t bones = s.boneCount();
  std::vector<std::vector<std::uint32_t>> joined(bones);
  auto near = [&](const Vec3& a, const Vec3& b) { return glm::length(a - b) <= tolerance; };
  for (std::size_t a = 0; a < bones; ++a) {
    for (std::size_t b = 0; b < bones; ++b) {
      const bool family = a == b || s.parents[a] == static_cast<std::int32_t>(b) ||
                          s.parents[b] == static_cast<std::int32_t>(a);
      const bool shared = near(s.heads[a], s.heads[b]) || near(s.heads[a], s.tails[b]) ||
                          near(s.tails[a], s.heads[b]) || near(s.tails[a], s.tails[b]);
      if (family || shared) joined[a].push_back(static_cast<std::uint32_t>(b));
    }
  }
  return joined;
}

}  // namespace

Result<Influences> distanceWeights(std::span<const Vec3> rest, const FaceList& faces, const Skeleton& skeleton,
                                   const DistanceWeightOptions& options) {
  ODESKIN_TRY(validateRig(Rig{skeleton, {}, {}}, 0, 0));
  if (options.max_influences < 1) {
    return invalidArgument("distance weights: max_influences must be at least 1, got " +
                           std::to_string(options.max_influences));
  }
  if (!std::isfinite(options.falloff_power) || !(options.falloff_power > 0.0)) {
    return invalidArgument("distance weights: falloff_power must be positive and finite, got " +
                           messageNumber(options.falloff_power));
  }
  if (options.smoothing_iterations < 0) {
    return invalidArgument("distance weights: smoothing_iterations must not be negative, got " +
                           std::to_string(options.smoothing_iterations));
  }
  ODESKIN_ASSIGN_OR_RETURN(const PositionBox bounds, checkedPositionBox(rest, "distance weights"));
  ODESKIN_TRY(checkFaces(faces, rest.size(), "distance weights"));

  const Vec3 size = bounds.hi - bounds.lo;
  const double box = rest.empty() ? 1.0 : std::max({size.x, size.y, size.z, std::numeric_limits<double>::min()});
  const double floor = kDistanceFloor * box;
  const std::vector<std::vector<std::uint32_t>> joined = joinedBones(skeleton, kJointTolerance * box);
  const std::size_t bones = skeleton.boneCount();

  std::vector<WeightRow> rows(rest.size());
  parallelFor(std::size_t{0}, rest.size(), [&](std::size_t i) {
    std::vector<double> distance(bones);
    std::size_t nearest = 0;
    for (std::size_t b = 0; b < bones; ++b) {
      distance[b] = std::max(segmentDistance(rest[i], skeleton.heads[b], skeleton.tails[b]), floor);
      if (distance[b] < distance[nearest]) nearest = b;
    }
    // Relative to the nearest distance, so the power cannot overflow or underflow.
    double sum = 0.0;
    for (const std::uint32_t b : joined[nearest]) {
      const double w = std::pow(distance[nearest] / distance[b], options.falloff_power);
      rows[i].push_back({b, w});
      sum += w;
    }
    for (BoneWeight& e : rows[i]) e.weight /= sum;
  });
  smoothRows(rows, vertexAdjacency(faces, rest.size()), options.smoothing_iterations, kSmoothingLambda);
  return pruneRows(rows, options.max_influences);
}

}  // namespace odeskin
