// SPDX-License-Identifier: MIT
#include "influences.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "lbs_job.hpp"

namespace odeskin {

std::uint32_t Influences::maxInfluences() const {
  std::uint32_t most = 0;
  for (std::size_t i = 0; i + 1 < offsets.size(); ++i) most = std::max(most, offsets[i + 1] - offsets[i]);
  return most;
}

Status validateBones(std::span<const BoneTransform> bones, const char* who) {
  for (std::size_t b = 0; b < bones.size(); ++b) {
    for (glm::length_t c = 0; c < 4; ++c) {
      if (!isFinite(bones[b][c])) return invalidArgument(std::string(who) + ": bone " + std::to_string(b) + " has a non-finite entry");
    }
  }
  return okStatus();
}

Status validateInfluences(const InfluencesView& influences, std::size_t vertex_count, std::uint32_t bone_count,
                          double sum_tolerance) {
  if (influences.offsets.size() != vertex_count + 1) {
    return invalidArgument("influences: offsets has " + std::to_string(influences.offsets.size()) +
                           " entries, expected vertex_count + 1 = " + std::to_string(vertex_count + 1));
  }
  if (influences.offsets[0] != 0) return invalidArgument("influences: offsets[0] must be 0");
  const std::size_t total = influences.offsets[vertex_count];
  if (influences.bones.size() != total || influences.weights.size() != total) {
    return invalidArgument("influences: bones/weights hold " + std::to_string(influences.bones.size()) + "/" +
                           std::to_string(influences.weights.size()) + " entries, offsets say " +
                           std::to_string(total));
  }
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const std::uint32_t begin = influences.offsets[i];
    const std::uint32_t end = influences.offsets[i + 1];
    if (end < begin) return invalidArgument("influences: offsets decrease at vertex " + std::to_string(i));
    // Only the last offset was checked against the arrays: a middle one past it (a corrupt file)
    // would index past bones and weights.
    if (end > total) {
      return invalidArgument("influences: offset " + std::to_string(end) + " of vertex " + std::to_string(i) +
                             " is past the " + std::to_string(total) + " entries");
    }
    if (end == begin) return invalidArgument("influences: vertex " + std::to_string(i) + " is bound to no bone");
    double sum = 0.0;
    for (std::uint32_t k = begin; k < end; ++k) {
      if (influences.bones[k] >= bone_count) {
        return invalidArgument("influences: vertex " + std::to_string(i) + " references bone " +
                               std::to_string(influences.bones[k]) + " of " + std::to_string(bone_count));
      }
      const double w = influences.weights[k];
      if (!std::isfinite(w) || w < 0.0) {
        return invalidArgument("influences: vertex " + std::to_string(i) + " has weight " + messageNumber(w));
      }
      sum += w;
    }
    if (std::abs(sum - 1.0) > sum_tolerance) {
      return invalidArgument("influences: weights of vertex " + std::to_string(i) + " sum to " +
                             messageNumber(sum) + ", not 1");
    }
  }
  return okStatus();
}

Influences influencesFromDense(std::span<const double> weights_vertex_major, std::size_t vertex_count,
                               std::uint32_t bone_count) {
  Influences out;
  out.offsets.assign(1, 0);
  out.offsets.reserve(vertex_count + 1);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    for (std::uint32_t b = 0; b < bone_count; ++b) {
      const double w = weights_vertex_major[i * bone_count + b];
      if (w != 0.0) {
        out.bones.push_back(b);
        out.weights.push_back(w);
      }
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.bones.size()));
  }
  return out;
}

Result<FixedSlotInfluences> toFixedSlots(const Influences& influences, std::uint32_t slots) {
  if (slots != 4 && slots != 8) {
    return invalidArgument("fixed influence slots must be 4 or 8, got " + std::to_string(slots));
  }
  const std::size_t vertex_count = influences.vertexCount();
  FixedSlotInfluences out;
  out.slots = slots;
  out.bones.assign(vertex_count * slots, 0);
  out.weights.assign(vertex_count * slots, 0.0f);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const std::uint32_t begin = influences.offsets[i];
    const std::uint32_t count = influences.offsets[i + 1] - begin;
    if (count > slots) {
      return invalidArgument("vertex " + std::to_string(i) + " has " + std::to_string(count) +
                             " influences, more than " + std::to_string(slots) + " slots: prune first");
    }
    for (std::uint32_t k = 0; k < count; ++k) {
      out.bones[i * slots + k] = influences.bones[begin + k];
      out.weights[i * slots + k] = static_cast<float>(influences.weights[begin + k]);
    }
  }
  return out;
}

Result<PrunedInfluences> pruneInfluences(const Influences& influences, std::uint32_t max_influences,
                                         std::span<const Vec3> rest_positions,
                                         std::span<const std::vector<BoneTransform>> poses) {
  if (max_influences == 0) return invalidArgument("prune: max_influences must be at least 1");
  const std::size_t vertex_count = influences.vertexCount();
  if (!poses.empty() && rest_positions.size() != vertex_count) {
    return invalidArgument("prune: " + std::to_string(rest_positions.size()) + " rest positions for " +
                           std::to_string(vertex_count) + " vertices");
  }
  PrunedInfluences out;
  Influences& pruned = out.influences;
  pruned.offsets.assign(1, 0);
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const std::uint32_t begin = influences.offsets[i];
    const std::uint32_t count = influences.offsets[i + 1] - begin;
    order.resize(count);
    std::iota(order.begin(), order.end(), begin);
    // Largest weights first; ties by bone index so the result does not depend on input order.
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      if (influences.weights[a] != influences.weights[b]) return influences.weights[a] > influences.weights[b];
      return influences.bones[a] < influences.bones[b];
    });
    const std::uint32_t kept = std::min(count, max_influences);
    double kept_sum = 0.0;
    for (std::uint32_t k = 0; k < kept; ++k) kept_sum += influences.weights[order[k]];
    double dropped = 0.0;
    for (std::uint32_t k = kept; k < count; ++k) dropped += influences.weights[order[k]];
    if (kept < count) ++out.report.vertices_pruned;
    out.report.max_dropped_weight = std::max(out.report.max_dropped_weight, dropped);
    for (std::uint32_t k = 0; k < kept; ++k) {
      pruned.bones.push_back(influences.bones[order[k]]);
      pruned.weights.push_back(kept_sum > 0.0 ? influences.weights[order[k]] / kept_sum : 1.0 / kept);
    }
    pruned.offsets.push_back(static_cast<std::uint32_t>(pruned.bones.size()));
  }
  for (const std::vector<BoneTransform>& pose : poses) {
    for (std::size_t i = 0; i < vertex_count; ++i) {
      if (influences.offsets[i + 1] - influences.offsets[i] <= max_influences) continue;
      const double error = glm::length(skinPoint(pruned, pose, i, rest_positions[i]) -
                                       skinPoint(influences, pose, i, rest_positions[i]));
      if (error > out.report.max_position_error) {
        out.report.max_position_error = error;
        out.report.worst_vertex = static_cast<std::uint32_t>(i);
      }
    }
  }
  return out;
}

}  // namespace odeskin
