// SPDX-License-Identifier: MIT
// C++ view of runtime_layout.h: std430 size checks and the float <-> ordered key conversion the
// bounds reduction of shaders/instanced_deform.comp uses.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

#include "../core/gpu_layout.hpp"
#include "runtime_layout.h"

namespace odeskin::gpu {

static_assert(sizeof(InstanceRecord) == 16);
static_assert(sizeof(Corner) == 8);
static_assert(sizeof(BoundsKeys) == 32);
static_assert(sizeof(InstancedPushConstants) == 48 && offsetof(InstancedPushConstants, basis_entries) == 36);
static_assert(sizeof(NormalsPushConstants) == 16);
static_assert(sizeof(GatherPushConstants) == 16);
static_assert(sizeof(TangentFrame) == 8 && sizeof(TangentWeights) == 8);
static_assert(sizeof(TangentsPushConstants) == 16);

inline constexpr uint kNoRates = ODESKIN_RT_NO_RATES;

// Unsigned key with key(a) < key(b) exactly when a < b for non-NaN floats (-0 sorts just below +0):
// negative floats have every bit flipped, positive ones only the sign bit.
constexpr uint orderedKey(float f) {
  const uint u = std::bit_cast<uint>(f);
  return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}
constexpr float fromOrderedKey(uint key) {
  return std::bit_cast<float>((key & 0x80000000u) != 0u ? (key & 0x7FFFFFFFu) : ~key);
}

}  // namespace odeskin::gpu
