// SPDX-License-Identifier: MIT
// The runtime on the CPU (DeformRuntime's API) for engines without compute: every instance is
// deformed by CpuDeformKernel (float32 at SIMD width, within float rounding of the shader and of the
// double reference), instances spread over the WorkerArena's threads, then normals and bounds per
// instance (instance_outputs.hpp); the instances left over after whole rounds of one per thread
// have their vertices spread over the threads instead. With RuntimeOptions::render_layout the
// outputs are then gathered into the asset's render vertices, and with RuntimeOptions::tangents the
// tangents computed in them. This backend is the reference of the instanced shaders
// (shaders/instanced_deform.comp, shaders/instance_normals.comp, shaders/render_gather.comp,
// shaders/instance_tangents.comp). submitFrame() does the work before it returns; wait() has nothing
// to wait for.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "deform_runtime.hpp"
#include "../kernels/cpu_deform_kernel.hpp"

namespace odeskin {

class CpuRuntime final : public DeformRuntime {
 public:
  // `asset` must outlive the runtime and stay where it is. kInvalidArgument for frames_in_flight = 0; kOutOfRange when
  // capacity x vertexCount() x frames_in_flight outputs do not fit a std::size_t.
  static Result<CpuRuntime> create(const RuntimeAsset& asset, const RuntimeOptions& options);

  CpuRuntime(CpuRuntime&&) noexcept = default;
  CpuRuntime& operator=(CpuRuntime&&) noexcept = default;

  std::string_view backendName() const override { return "cpu"; }
  Status wait() override { return okStatus(); }
  RuntimeMemory memory() const override;

  // Zero-copy views of a finished frame's outputs, valid until its slot is reused (framesInFlight()
  // submissions later): every instance's positions (instance k at k * outputVertexCount()),
  // likewise normals and tangents (empty when off). kInvalidArgument as readPositions for a frame
  // not held.
  Result<std::span<const gpu::Float4>> positions(std::uint64_t frame);
  Result<std::span<const gpu::Float4>> normals(std::uint64_t frame);
  Result<std::span<const gpu::Float4>> tangents(std::uint64_t frame);

 protected:
  Status submitSlot(std::uint32_t slot, std::uint32_t instance_count, FrameTimes& times) override;
  Status waitSlot(std::uint32_t) override { return okStatus(); }
  Status copyPositions(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) override;
  Status copyNormals(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) override;
  Status copyTangents(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) override;
  Status copyBounds(std::uint32_t slot, std::span<InstanceBounds> out) override;
  double deviceSeconds(std::uint32_t) const override { return 0.0; }

 private:
  CpuRuntime(const RuntimeAsset& asset, const RuntimeOptions& options) : DeformRuntime(asset, options) {}

  struct Slot {
    std::vector<gpu::Float4> positions;  // capacity x V
    std::vector<gpu::Float4> normals;    // capacity x V, or empty
    std::vector<InstanceBounds> bounds;  // capacity
    // The outputs in render vertices (capacity x R) when gathersRenderVertices(), else empty.
    std::vector<gpu::Float4> render_positions;
    std::vector<gpu::Float4> render_normals;
    std::vector<gpu::Float4> tangents;  // capacity x outputVertexCount(), when tangents are on
    std::uint32_t instance_count = 0;

    const std::vector<gpu::Float4>& outPositions() const { return render_positions.empty() ? positions : render_positions; }
    const std::vector<gpu::Float4>& outNormals() const { return render_positions.empty() ? normals : render_normals; }
  };

  // Instances [first, end), fewer than threads: each one's deformation spreads over the arena,
  // then its normals and bounds in vertex chunks.
  Status deformSpread(Slot& slot, std::uint32_t first, std::uint32_t end);
  // Instances [first, end) deformed on the arena, one instance per task, each on `threads` (the
  // kernel's meaning); with `outputs`, its normals and bounds too, while its positions are in cache.
  Status deformInstances(Slot& slot, std::uint32_t first, std::uint32_t end, unsigned threads, bool outputs);
  Status deformInstance(Slot& slot, std::size_t k, unsigned threads);
  // Output vertices [begin, end) of instance k from its topology outputs: the render vertices'
  // positions and normals (gathersRenderVertices()) and the tangents (options().tangents).
  void finishInstance(Slot& slot, std::size_t k, std::size_t begin, std::size_t end) const;
  // Whether finishInstance has work: it runs after every topology normal of its instance.
  bool finishes() const { return gathersRenderVertices() || options().tangents; }

  std::vector<CpuDeformKernel> deformers_;  // one per material preset (the SIMD kernel, prepared once)
  // This frame's inputs; one set suffices, since the frame is done when submitFrame returns.
  std::vector<gpu::InstanceRecord> records_;
  std::vector<gpu::BoneMatrix> bones_;
  std::vector<gpu::ModeBasis> basis_;
  std::vector<Slot> slots_;
  // Bounds of each vertex chunk of each instance that deformSpread takes (fewer than threads).
  std::vector<InstanceBounds> chunk_bounds_;
};

}  // namespace odeskin
