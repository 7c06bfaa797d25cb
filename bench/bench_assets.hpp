// SPDX-License-Identifier: MIT
// Benchmark inputs: one fitted procedural arm per (V, N) with its frame inputs, verified on every
// backend before anything is timed (STYLE.md: bench verifies before timing, as uVkCompute does).
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/kernels/cpu_deform_kernel.hpp"
#include "engine/kernels/fourier_deform_job.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "engine/offline/deform_asset.hpp"
#include "host/device.hpp"
#include "host/gpu_deformer.hpp"
#include "host/gpu_lbs.hpp"

namespace odeskin::bench {

// Ring size of every benchmark arm; V = rings * kRingVertices.
inline constexpr std::uint32_t kRingVertices = 64;
// The nominal size that stands for shared/data/cat-poses (10 poses, 7,207 vertices) fitted by the
// whole pipeline (automatic rig, 32 bones), when setCatDirectory named its folder: a real mesh,
// whose curve pairs do not fill whole 16-vertex blocks and whose blocks span several bones.
inline constexpr std::uint32_t kCatVertices = 7207;
void setCatDirectory(std::string dir);
bool hasCatDirectory();

// Worst |backend - cpu_ref| allowed, as a fraction of the bounding box's longest side.
inline constexpr double kVerifyTolerance = 1e-4;

// Everything one frame of either kernel reads, at (segment, tau) = the middle of the animation.
struct BenchAsset {
  std::uint32_t vertex_count = 0;    // V
  int modes = 0;                     // N
  DeformAsset asset;                 // double, for the reference jobs
  PackedDeformData packed;           // float32, for the fast path and the GPU
  std::uint32_t segment = 0;
  std::vector<ModeBasisValue> basis;
  std::vector<BoneTransform> bones;
  std::vector<gpu::ModeBasis> gpu_basis;
  std::vector<gpu::BoneMatrix> gpu_bones;
  std::optional<CpuDeformKernel> kernel;     // prepared from `packed` before timing
  std::optional<GpuDeformer> gpu_deformer;  // empty without a Vulkan device
  std::optional<GpuLbs> gpu_lbs;
  // Worst error found by verification, / longest box side (reported in the summary).
  double fast_error = 0.0;
  double gpu_error = 0.0;
  double lbs_fast_error = 0.0;
  double lbs_gpu_error = 0.0;
  double kernel_error = 0.0;
  double lbs_kernel_error = 0.0;
};

// The Vulkan device shared by every GPU case, opened once; nullptr when there is none
// (benchDeviceNote() then says why, else it is the device name). Its objects must go before it:
// call releaseAll() before main returns.
const vk::Device* benchDevice();
const std::string& benchDeviceNote();

// The asset for (V, N): built (fit, pack, GPU upload) and verified the first time it is asked
// for. Only the latest (V, N) is kept, because a 1e6-vertex asset is hundreds of MB and the cases
// run grouped by (V, N); a verification failure prints the worst vertex and exits with code 3.
BenchAsset& benchAsset(std::uint32_t vertex_count, int modes);

// Every verified (V, N) with its errors, for the summary (the assets themselves are released).
struct VerifiedSize {
  std::uint32_t vertex_count = 0;
  int modes = 0;
  double fast_error = 0.0, gpu_error = 0.0, lbs_fast_error = 0.0, lbs_gpu_error = 0.0;
  double kernel_error = 0.0, lbs_kernel_error = 0.0;
  CpuDeformKernel::Stats kernel_stats;
  CpuKernelArch kernel_arch = CpuKernelArch::kGeneric;
  double build_seconds = 0.0;
};
const std::vector<VerifiedSize>& verifiedSizes();

// Drops the cached asset and GPU objects, then the device.
void releaseAll();

}  // namespace odeskin::bench
