// SPDX-License-Identifier: MIT
// The per-frame cases of `odeskin bench`: odeskin deformation (skinning included), plain LBS and
// DQS on the same tiled mesh, per backend (cpu_ref: the double reference; cpu_fast: CpuDeformKernel,
// the float SIMD path, with 1 and all threads; vulkan: one dispatch per frame). Every backend's frame
// is checked against cpu_ref before it is timed; upload (GPU) or preparation (CpuDeformKernel::create)
// is timed apart from the frames. Each odeskin case on cpu_fast and vulkan then runs again,
// alternating with LBS frames of the same mesh, for the frame-against-frame ratio (PairedTiming).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "engine/core/result.hpp"
#include "engine/offline/deform_asset.hpp"
#include "host/device.hpp"

namespace odeskin::bench {

// Worst |backend - cpu_ref| allowed before timing, as a fraction of the longest box side.
inline constexpr double kVerifyTolerance = 1e-4;

struct DeformCaseOptions {
  std::vector<std::size_t> sizes;            // vertex counts
  std::vector<int> terms;                    // N; each needs an asset in the sources
  bool cpu_ref = true;
  bool cpu_fast = true;
  bool vulkan = true;
  unsigned all_threads = 0;                  // cpu_fast's "all threads" count; <= 1: not run
  double min_seconds = 0.25;                 // per case, of timed frames
  double time = 1.5;                         // global animation time of the frame (segment + tau)
  const vk::Device* device = nullptr;        // vulkan cases need it
  std::function<void(const std::string&)> progress;  // one line per case, optional
};

// `sources` maps N to a fitted asset with that N (the mesh that gets tiled). Records are appended
// to `out` as they finish. kInvalidArgument when a case's N has no source or vulkan is asked
// without a device; kInternal (naming backend, size and error) when a backend fails verification.
Status runDeformCases(const std::map<int, DeformAsset>& sources, const DeformCaseOptions& options,
                      std::vector<BenchRecord>& out);

}  // namespace odeskin::bench
