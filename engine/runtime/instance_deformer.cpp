// SPDX-License-Identifier: MIT
#include "instance_deformer.hpp"

#include <vector>

#include "../kernels/fourier_deform_fast_job.hpp"

namespace odeskin {

Result<InstanceDeformer> InstanceDeformer::create(const PackedDeformData& data) {
  std::vector<gpu::BoneMatrix> bones(data.bone_count);
  std::vector<gpu::ModeBasis> basis(ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes}));
  std::vector<gpu::Float4> out(data.vertex_count);
  FourierDeformFastJob job;
  job.data = &data;
  job.bones = bones;
  job.basis = basis;
  job.out_positions = out;
  ODESKIN_TRY(job.validate());
  InstanceDeformer deformer;
  deformer.data_ = &data;
  return deformer;
}

Status InstanceDeformer::deform(std::uint32_t segment, std::span<const gpu::BoneMatrix> bones,
                                std::span<const gpu::ModeBasis> basis, std::span<gpu::Float4> out,
                                unsigned threads) const {
  FourierDeformFastJob job;
  job.data = data_;
  job.segment = segment;
  job.bones = bones;
  job.basis = basis;
  job.out_positions = out;
  job.threads = threads;
  return job.run();
}

}  // namespace odeskin
