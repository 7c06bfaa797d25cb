// SPDX-License-Identifier: MIT
// Fast CPU path (float, multithreaded) of fourier_deform_job: the same mathematics in the order of
// operations of shaders/fourier_deform.comp (each curve's coefficients folded with the time basis as
// shaders/fold_series.comp folds them, cos/sin by the angle-addition recurrence, curve series
// blended before skinning), so CPU-fast, GPU and reference agree within float32 tolerances.
// Skinning follows data->skinning, as the GPU does (one source, so the two cannot disagree): with
// SkinningMode::kDualQuaternion each run converts the frame's bones once (toGpuDualQuaternions,
// bone_count entries allocated per run) and blends them per vertex (dual_quaternion.hpp).
#pragma once

#include <cstdint>
#include <span>

#include "../core/status.hpp"
#include "packed_deform.hpp"

namespace odeskin {

struct FourierDeformFastJob {
  const PackedDeformData* data = nullptr;   // required
  std::uint32_t segment = 0;                // < data->segment_count
  std::span<const gpu::BoneMatrix> bones;   // data->bone_count, required: M_b(tau)
  std::span<const gpu::ModeBasis> basis;    // data->material_count * (N+1), required
  std::span<gpu::Float4> out_positions;     // data->vertex_count, required
  unsigned threads = 0;                     // worker threads; 0 = all, more than usableThreads are capped

  // kInvalidArgument naming the field whose size is wrong, or an unknown data->skinning (sizes
  // only: indices inside `data` are checked once by packDeformAsset, not per frame).
  Status validate() const;
  Status run() const;
};

// Plain skinning on the same packed data (no residual), the baseline of every speed ratio: LBS, or
// dual-quaternion skinning when data->skinning says so.
struct LbsFastJob {
  const PackedDeformData* data = nullptr;   // required (rest positions and influences)
  std::span<const gpu::BoneMatrix> bones;   // data->bone_count
  std::span<gpu::Float4> out_positions;     // data->vertex_count
  unsigned threads = 0;

  Status validate() const;
  Status run() const;
};

}  // namespace odeskin
