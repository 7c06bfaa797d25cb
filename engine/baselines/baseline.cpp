// SPDX-License-Identifier: MIT
#include "baseline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "../core/finite_vector.hpp"

namespace odeskin {
namespace {

constexpr std::array<std::string_view, kBaselineMethodCount> kNames = {
    "linear", "lbs", "dqs", "psd_lbs", "psd_dqs", "fd_curve", "odeskin_static", "odeskin_dynamic"};

}  // namespace

std::string_view baselineMethodName(BaselineMethod method) {
  const auto index = static_cast<std::uint32_t>(method);
  return index < kNames.size() ? kNames[index] : std::string_view("unknown");
}

bool parseBaselineMethod(std::string_view name, BaselineMethod* method) {
  for (std::uint32_t i = 0; i < kNames.size(); ++i) {
    if (kNames[i] == name) {
      *method = static_cast<BaselineMethod>(i);
      return true;
    }
  }
  return false;
}

std::pair<std::uint32_t, double> locateSegment(double t, std::uint32_t segment_count) {
  if (segment_count == 0) return {0, 0.0};
  const double end = static_cast<double>(segment_count);
  const double clamped = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, end);
  const std::uint32_t segment = std::min(static_cast<std::uint32_t>(clamped), segment_count - 1);
  return {segment, clamped - segment};
}

Status checkKeyPoses(const std::vector<std::vector<Vec3>>& keys, std::size_t vertex_count, const char* who) {
  const std::string prefix = std::string(who) + ": ";
  if (keys.size() < 2) return invalidArgument(prefix + "needs at least 2 key poses, got " + std::to_string(keys.size()));
  const std::size_t v_count = vertex_count > 0 ? vertex_count : keys[0].size();
  if (v_count == 0) return invalidArgument(prefix + "the key poses have no vertices");
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (keys[k].size() != v_count) {
      return invalidArgument(prefix + "key " + std::to_string(k) + " has " + std::to_string(keys[k].size()) +
                             " vertices, expected " + std::to_string(v_count));
    }
    for (std::size_t i = 0; i < v_count; ++i) {
      const Vec3& p = keys[k][i];
      if (!isFinite(p)) {
        return invalidArgument(prefix + "key " + std::to_string(k) + " vertex " + std::to_string(i) + " is not finite");
      }
    }
  }
  return okStatus();
}

Status Baseline::checkFrame(const BaselineFrameInput& frame, std::span<const Vec3> out, std::uint32_t segment_count,
                            std::size_t bone_count) const {
  const std::string who = std::string(name()) + ": ";
  if (out.size() != vertex_count_) {
    return invalidArgument(who + "output has " + std::to_string(out.size()) + " positions, the mesh " +
                           std::to_string(vertex_count_) + " vertices");
  }
  if (frame.segment >= segment_count) {
    return outOfRange(who + "segment " + std::to_string(frame.segment) + " of " + std::to_string(segment_count));
  }
  if (!std::isfinite(frame.tau)) return invalidArgument(who + "tau is not finite");
  if (bone_count > 0 && !frame.bones.empty() && frame.bones.size() != bone_count) {
    return invalidArgument(who + std::to_string(frame.bones.size()) + " bone transforms for a rig of " +
                           std::to_string(bone_count) + " bones");
  }
  return okStatus();
}

}  // namespace odeskin
