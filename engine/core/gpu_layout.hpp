// SPDX-License-Identifier: MIT
// C++ view of gpu_layout.h with the std430 size checks the GLSL side relies on.
#pragma once

#include <cstddef>

#include "gpu_layout.h"

namespace odeskin::gpu {

static_assert(sizeof(Float4) == 16);
static_assert(sizeof(VertexBinding) == 16 && offsetof(VertexBinding, v) == 12);
static_assert(sizeof(SegmentVertex) == 16 && offsetof(SegmentVertex, remainder_index) == 12);
static_assert(sizeof(Influence) == 8);
static_assert(sizeof(BoneMatrix) == 48);
static_assert(sizeof(DualQuat) == 32 && offsetof(DualQuat, dual) == 16);
static_assert(sizeof(ModeBasis) == 8);
static_assert(sizeof(DeformPushConstants) == 48 && sizeof(DeformPushConstants) <= 128);
static_assert(offsetof(DeformPushConstants, skinning) == 40);
static_assert(sizeof(FoldPushConstants) == 16);

inline constexpr uint kWorkgroupSize = ODESKIN_WORKGROUP_SIZE;
// Workgroups of kWorkgroupSize invocations that cover `count` items (a dispatch's x extent).
constexpr uint workgroupsFor(uint count) { return (count + kWorkgroupSize - 1) / kWorkgroupSize; }
inline constexpr uint kNoRemainder = ODESKIN_NO_REMAINDER;

// Coefficients per curve for N modes (layout described in gpu_layout.h).
constexpr uint coefficientsPerCurve(uint modes) { return 2 * modes + 2; }

}  // namespace odeskin::gpu
