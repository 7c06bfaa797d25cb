// SPDX-License-Identifier: MIT
// CPU fast path for many frames of one asset: the mathematics of FourierDeformFastJob (thesis Eq
// 6.30 corrected, MATH.md 5.6; PIPELINE.md 3, in float32 with the shader's cos/sin recurrence),
//   D = (1 - w) S_a(v) + w S_b(v),  S_c(v) = sum_m (gamma_n d_cm + psi_n rdot_cm) phi_m(v)
//   bind: out = skin(X + r^s + D + gamma_rem eps);  posed: out = skin(X) + r^s + D + gamma_rem eps
// on data reorganised once by create() so that a frame runs at SIMD width (AVX-512, AVX2 + FMA, or
// portable 4-lane vectors, chosen at run time; the default build stays baseline x86-64):
//  - vertices are sorted by curve pair and cut into blocks of 16 that share the pair, so the
//    series coefficients are broadcast scalars;
//  - each frame folds gamma_n / psi_n into every curve's coefficients once per curve (O(C N)), not
//    once per vertex, and the series stops at each curve's last non-zero harmonic;
//  - cos/sin(2 pi v) are precomputed per vertex (in double), the recurrence continues from them;
//  - skinning sums the block's union of bones with dense per-lane weights (see
//    simd_deform_layout.hpp), which covers the sparse, 4- and 8-slot influence layouts alike.
// Results agree with FourierDeformFastJob and FourierDeformJob within float32 rounding (the
// tests assert 1e-5 of the bounding box); they are not bit-identical to either.
//
// Thread safety: a kernel is immutable after create(); any number of threads may call deform()
// and skin() on one kernel at once (many instances of one asset), each with its own output.
// Per-call memory: none on the heap for linear blend skinning. Dual-quaternion skinning converts
// the frame's bones on the stack up to kMaxStackBones bones and on the heap above that, unless the
// caller passes the dual quaternions itself (the overload of deform and skin that takes them).
// threads: 1 runs on the calling thread; 0 runs on the caller's current TBB arena (all hardware
// threads by default); n > 1 creates a TBB arena of n threads for the call, at most usableThreads
// (engine/core/thread_count.hpp): the machine's, or what a tbb::global_control allows.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/status.hpp"
#include "packed_deform.hpp"

namespace odeskin {

namespace simd_deform {
struct Layout;
}

// Instruction sets of the block loops, slowest first.
enum class CpuKernelArch : std::uint8_t {
  kGeneric,  // 4-lane GCC/Clang vectors: SSE2 on x86-64, NEON on ARM
  kAvx2,     // 8 lanes, AVX2 + FMA (x86-64-v3)
  kAvx512,   // 16 lanes, AVX-512 F/CD/BW/DQ/VL (x86-64-v4)
};

const char* cpuKernelArchName(CpuKernelArch arch);
// The instruction sets this build and this CPU can both run, fastest first (always ends with
// kGeneric). The environment variable ODESKIN_CPU_KERNEL_ARCH=generic|avx2|avx512 caps the choice of
// create(data) (for comparisons); it never selects what the CPU lacks, and another value makes
// create(data) fail (kInvalidArgument).
std::vector<CpuKernelArch> supportedCpuKernelArchs();

class CpuDeformKernel {
 public:
  // Bones a dual-quaternion frame converts on the stack (32 bytes each).
  static constexpr std::uint32_t kMaxStackBones = 256;

  // Prepares `data` (copied and reorganised; `data` may be freed afterwards) for the fastest
  // supported instruction set. kInvalidArgument naming the element for what FourierDeformFastJob
  // would misread: an influence layout other than 0, 4 or 8, an unknown skinning mode, array sizes
  // that disagree with the counts, a curve, material, bone or remainder index out of range, a
  // non-finite binding; kOutOfRange for N > 64.
  static Result<CpuDeformKernel> create(const PackedDeformData& data);
  // The same for one instruction set; kUnavailable if this build or CPU cannot run it.
  static Result<CpuDeformKernel> create(const PackedDeformData& data, CpuKernelArch arch);

  CpuDeformKernel(CpuDeformKernel&&) noexcept;
  CpuDeformKernel& operator=(CpuDeformKernel&&) noexcept;
  ~CpuDeformKernel();

  // One frame of segment `segment`: bones (bone_count, M_b(tau)), basis (material_count x (N+1) + 1
  // entries, toGpuBasis of DeformPlayer::basisAt), out_positions (vertex_count, written in the
  // mesh's vertex order as (x, y, z, 1)). kInvalidArgument naming the span whose size is wrong or
  // the segment out of range, as FourierDeformFastJob::validate says it; nothing is written then.
  Status deform(std::uint32_t segment, std::span<const gpu::BoneMatrix> bones, std::span<const gpu::ModeBasis> basis,
                std::span<gpu::Float4> out_positions, unsigned threads = 1) const;
  // Dual-quaternion skinning with the frame's bones already converted by toGpuDualQuaternions
  // (bone_count entries, the same bones): no conversion, no allocation. With linear skinning
  // dual_quats is ignored and may be empty.
  Status deform(std::uint32_t segment, std::span<const gpu::BoneMatrix> bones,
                std::span<const gpu::DualQuat> dual_quats, std::span<const gpu::ModeBasis> basis,
                std::span<gpu::Float4> out_positions, unsigned threads = 1) const;

  // Plain skinning of the rest positions (LBS or DQS per data.skinning), no residual: the
  // baseline of the deformation's cost, on the same blocks and instruction set.
  Status skin(std::span<const gpu::BoneMatrix> bones, std::span<gpu::Float4> out_positions, unsigned threads = 1) const;
  Status skin(std::span<const gpu::BoneMatrix> bones, std::span<const gpu::DualQuat> dual_quats,
              std::span<gpu::Float4> out_positions, unsigned threads = 1) const;

  std::uint32_t vertexCount() const;
  CpuKernelArch arch() const { return arch_; }

  // How well the data fits the blocks, for reports: padded lanes cost as much as real ones.
  struct Stats {
    std::size_t blocks = 0;
    std::size_t lanes = 0;             // lanes computed, padding included (depends on the instruction set)
    std::size_t two_curve_blocks = 0;  // blocks whose pair has two distinct curves
    double mean_union_bones = 0.0;     // bones per block (skinning costs 12 FMAs per lane each)
    std::size_t bytes = 0;             // memory held by the kernel
  };
  Stats stats() const;

 private:
  CpuDeformKernel(std::unique_ptr<const simd_deform::Layout> layout, CpuKernelArch arch);
  Status run(bool deform, std::uint32_t segment, std::span<const gpu::BoneMatrix> bones,
             std::span<const gpu::DualQuat> dual_quats, std::span<const gpu::ModeBasis> basis,
             std::span<gpu::Float4> out_positions, unsigned threads) const;

  std::unique_ptr<const simd_deform::Layout> layout_;
  CpuKernelArch arch_ = CpuKernelArch::kGeneric;
};

}  // namespace odeskin
