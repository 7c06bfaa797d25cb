// SPDX-License-Identifier: MIT
// What one benchmark size deforms: a fitted real mesh tiled to the requested vertex count
// (tiled_asset.hpp), packed for the fast path and the GPU, with one frame's inputs prepared once
// (time basis and bone matrices cost O(B + N) per frame, not O(V), so they stay outside the timing).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/result.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "engine/offline/deform_asset.hpp"

namespace odeskin::bench {

// One frame's inputs in double (reference) and float (fast path, GPU).
struct BenchFrame {
  std::uint32_t segment = 0;
  std::vector<ModeBasisValue> basis;
  std::vector<BoneTransform> bones;
  std::vector<gpu::ModeBasis> gpu_basis;
  std::vector<gpu::BoneMatrix> gpu_bones;
};

struct BenchSubject {
  DeformAsset asset;        // double, for the reference kernels
  PackedDeformData packed;  // float32, for the fast path and the GPU
  BenchFrame frame;

  std::uint32_t vertexCount() const { return packed.vertex_count; }
};

// The frame of `asset` at global time t (segment + tau, DeformPlayer::locate).
Result<BenchFrame> benchFrame(const DeformAsset& asset, double t);

// `source` tiled to `vertex_count` vertices, with `skinning` (LBS or DQS), packed, at time t.
Result<BenchSubject> makeSubject(const DeformAsset& source, std::size_t vertex_count, SkinningMode skinning, double t);

}  // namespace odeskin::bench
