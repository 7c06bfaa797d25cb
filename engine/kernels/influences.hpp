// SPDX-License-Identifier: MIT
// Skinning influences: any number per vertex in compressed sparse rows, fixed-slot layouts for the
// 4- and 8-influence fast paths, and pruning to K influences with its error reported.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

// Compressed sparse rows: the influences of vertex i are [offsets[i], offsets[i+1]).
struct Influences {
  std::vector<std::uint32_t> offsets{0};  // vertex_count + 1, offsets[0] = 0, non-decreasing
  std::vector<std::uint32_t> bones;       // offsets.back() bone indices
  std::vector<double> weights;            // offsets.back() weights, >= 0, summing to 1 per vertex

  std::size_t vertexCount() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::uint32_t maxInfluences() const;
};

struct InfluencesView {
  std::span<const std::uint32_t> offsets;
  std::span<const std::uint32_t> bones;
  std::span<const double> weights;

  InfluencesView() = default;
  InfluencesView(const Influences& in) : offsets(in.offsets), bones(in.bones), weights(in.weights) {}  // cppcheck-suppress noExplicitConstructor ; NOLINT: implicit by design
};

// Checks the layout for `vertex_count` vertices and `bone_count` bones.
// kInvalidArgument: wrong offsets size or order, bone index >= bone_count, negative or non-finite
// weight, a vertex with no influence, or weights not summing to 1 within `sum_tolerance`.
Status validateInfluences(const InfluencesView& influences, std::size_t vertex_count,
                          std::uint32_t bone_count, double sum_tolerance = 1e-6);

// kInvalidArgument "<who>: bone B has a non-finite entry": LBS would spread the NaN, and dual
// quaternions would take the bone for the identity (nearestRotation's fallback) without a word.
Status validateBones(std::span<const BoneTransform> bones, const char* who);

// Builds rows from dense per-vertex (bone, weight) lists, dropping zero weights.
Influences influencesFromDense(std::span<const double> weights_vertex_major, std::size_t vertex_count,
                               std::uint32_t bone_count);

// Fixed-slot layout: `slots` entries per vertex (4 or 8), padded with (bone 0, weight 0).
struct FixedSlotInfluences {
  std::uint32_t slots = 0;
  std::vector<std::uint32_t> bones;  // vertex_count * slots
  std::vector<float> weights;        // vertex_count * slots
};
// kInvalidArgument when slots is not 4 or 8, or some vertex has more than `slots` influences
// (prune first).
Result<FixedSlotInfluences> toFixedSlots(const Influences& influences, std::uint32_t slots);

// Keeps the `max_influences` largest weights per vertex and renormalises them to sum to 1.
struct PruneReport {
  std::uint32_t vertices_pruned = 0;     // vertices that lost at least one influence
  double max_dropped_weight = 0.0;       // largest total weight removed from one vertex
  double max_position_error = 0.0;       // max |LBS_pruned - LBS_full| over the given poses
  std::uint32_t worst_vertex = 0;        // where max_position_error occurs
};
struct PrunedInfluences {
  Influences influences;
  PruneReport report;
};
// `poses`: bone transform sets (each bone_count long) at which the position error is measured on
// `rest_positions` (may be empty: then only the dropped weight is reported).
// kInvalidArgument: max_influences == 0 or sizes disagree.
Result<PrunedInfluences> pruneInfluences(const Influences& influences, std::uint32_t max_influences,
                                         std::span<const Vec3> rest_positions,
                                         std::span<const std::vector<BoneTransform>> poses);

}  // namespace odeskin
