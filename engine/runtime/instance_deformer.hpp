// SPDX-License-Identifier: MIT
// The CPU deformation of one instance, kept in this one place so a faster kernel replaces one body:
// today a FourierDeformFastJob per call; next, CpuDeformKernel (engine/kernels/cpu_deform_kernel.hpp),
// whose create() and deform() have these very signatures.
#pragma once

#include <cstdint>
#include <span>

#include "../core/result.hpp"
#include "../kernels/packed_deform.hpp"

namespace odeskin {

class InstanceDeformer {
 public:
  // `data` must outlive the deformer. kInvalidArgument as FourierDeformFastJob::validate for
  // inconsistent packed data (checked once here, with segment 0).
  static Result<InstanceDeformer> create(const PackedDeformData& data);

  // Positions of `segment` with `bones` (bone_count) and `basis` (basis entries) into `out`
  // (vertex_count), on `threads` threads (0: the calling arena's). kInvalidArgument naming a wrong size.
  Status deform(std::uint32_t segment, std::span<const gpu::BoneMatrix> bones, std::span<const gpu::ModeBasis> basis,
                std::span<gpu::Float4> out, unsigned threads) const;

 private:
  const PackedDeformData* data_ = nullptr;
};

}  // namespace odeskin
