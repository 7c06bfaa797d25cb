// SPDX-License-Identifier: MIT
// What the Vulkan runtime tests check a frame against: CpuRuntime, instance for instance. Positions
// within 1e-5 of the bounding box's longest side (both float32 in the same order of operations; the
// gap is the GPU's cos/sin and fused multiply-adds), normals within 1e-3 (unit vectors rebuilt from
// those positions: short edges amplify the positions' gap), bounds exactly the min and max of the
// GPU's own positions.
#pragma once

#include <algorithm>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/runtime/deform_runtime.hpp"
#include "runtime_fixtures.hpp"

namespace odeskin::testing {

inline constexpr double kPositionTolerance = 1e-5;  // x the longest box side
inline constexpr double kNormalTolerance = 1e-3;    // absolute, on unit normals

inline RuntimeOptions withCapacity(std::uint32_t capacity) {
  RuntimeOptions options;
  options.capacity = capacity;
  return options;
}

// The same instance states on both backends.
inline void setBoth(DeformRuntime& a, DeformRuntime& b, std::uint32_t index, const InstanceState& state) {
  ASSERT_TRUE(a.setInstance(index, state).ok());
  ASSERT_TRUE(b.setInstance(index, state).ok());
}

inline std::vector<gpu::Float4> read(DeformRuntime& rt, std::uint64_t frame, std::uint32_t instance, bool normals = false) {
  std::vector<gpu::Float4> out(rt.outputVertexCount());
  const Status status = normals ? rt.readNormals(frame, instance, out) : rt.readPositions(frame, instance, out);
  EXPECT_TRUE(status.ok()) << status.toString();
  return out;
}

inline InstanceBounds boxOf(std::span<const gpu::Float4> positions) {
  InstanceBounds b;
  for (const gpu::Float4& p : positions) {
    b.min = glm::min(b.min, glm::vec3(p.x, p.y, p.z));
    b.max = glm::max(b.max, glm::vec3(p.x, p.y, p.z));
  }
  return b;
}

// Frame `gpu_frame` of `gpu` against frame `cpu_frame` of `cpu`, instance by instance.
inline void expectSameFrame(DeformRuntime& cpu, std::uint64_t cpu_frame, DeformRuntime& gpu, std::uint64_t gpu_frame,
                     std::uint32_t count, const std::string& what) {
  const double box = longestBoxSide(cpu.asset().source().rest_positions);
  std::vector<InstanceBounds> gpu_bounds(count), cpu_bounds(count);
  ASSERT_TRUE(gpu.readBounds(gpu_frame, gpu_bounds).ok());
  ASSERT_TRUE(cpu.readBounds(cpu_frame, cpu_bounds).ok());
  double worst_position = 0.0, worst_normal = 0.0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const auto expected = read(cpu, cpu_frame, k);
    const auto actual = read(gpu, gpu_frame, k);
    const auto gap = worstGap(expected, actual);
    EXPECT_LT(gap.gap / box, kPositionTolerance) << what << " instance " << k << ": worst vertex " << gap.vertex;
    worst_position = std::max(worst_position, gap.gap / box);
    if (gpu.options().normals) {
      const auto normal_gap = worstGap(read(cpu, cpu_frame, k, true), read(gpu, gpu_frame, k, true));
      EXPECT_LT(normal_gap.gap, kNormalTolerance) << what << " instance " << k << ": worst normal " << normal_gap.vertex;
      worst_normal = std::max(worst_normal, normal_gap.gap);
    }
    // The GPU's reduction gives exactly the min and max of what it wrote.
    const InstanceBounds own = boxOf(actual);
    EXPECT_EQ(gpu_bounds[k].min, own.min) << what << " instance " << k;
    EXPECT_EQ(gpu_bounds[k].max, own.max) << what << " instance " << k;
    EXPECT_LT(glm::length(glm::dvec3(gpu_bounds[k].max - cpu_bounds[k].max)) / box, kPositionTolerance);
  }
  std::printf("%s: max |vulkan - cpu| / box = %.2e, normals %.2e\n", what.c_str(), worst_position, worst_normal);
}

}  // namespace odeskin::testing
