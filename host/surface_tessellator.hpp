// SPDX-License-Identifier: MIT
// GPU dispatcher of the network tessellation (shaders/ode6_tessellate.comp; thesis ch. 4, Eq 4.8):
// the same network and resolution as tessellateNetwork (engine/surfaces/tessellation.hpp), the same
// welded grid out, in float. create() packs and uploads the network (packTessellation); run()
// records both passes (cardinal table, then vertices) in one command buffer with a barrier between,
// bracketed by timestamps, submits and waits; read*() copy results back.
#pragma once

#include <cstdint>
#include <span>

#include "buffer.hpp"
#include "compute_pipeline.hpp"
#include "device.hpp"
#include "engine/core/gpu_layout.h"
#include "engine/core/result.hpp"
#include "engine/surfaces/tessellation_gpu.hpp"
#include "timestamp_queries.hpp"
#include "vk_handle.hpp"

namespace odeskin {

class SurfaceTessellator {
 public:
  // Errors of packTessellation (kInvalidArgument, kOutOfRange); kUnavailable when a buffer exceeds
  // maxStorageBufferRange; kDeviceError from the driver. `device` must outlive the object.
  static Result<SurfaceTessellator> create(const vk::Device& device, const Network& network,
                                           TessellationResolution resolution);

  // Both passes; waits for them. lastGpuSeconds() then holds their timestamp time.
  Status run();

  // out: grid().vertexCount() entries, xyz = S, w = 1; after run().
  Status readPositions(std::span<gpu::Float4> out) const;
  // out: cardinal sets x u_samples x 6 entries, g_k(u_i) at [(set u_samples + i) 6 + k - 1].
  Status readCardinalTable(std::span<float> out) const;

  const TessellationGrid& grid() const { return data_.grid; }
  std::size_t cardinalTableSize() const { return data_.tableFloats(); }
  double lastGpuSeconds() const { return last_gpu_seconds_; }

 private:
  SurfaceTessellator() = default;

  const vk::Device* device_ = nullptr;
  TessellationGpuData data_;
  vk::Buffer cardinals_;
  vk::Buffer patch_cardinals_;
  vk::Buffer boundary_samples_;
  vk::Buffer table_;
  vk::Buffer positions_;
  vk::TimestampQueries timestamps_;
  vk::ComputePipeline pipeline_;        // the cardinal pass; owns the layout and descriptor set
  vk::UniquePipeline vertex_pipeline_;  // the vertex pass: same layout, kPass specialized
  double last_gpu_seconds_ = 0.0;
};

}  // namespace odeskin
