// SPDX-License-Identifier: MIT
#include "cpu_runtime.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <mutex>
#include <new>
#include <string>

#include "../core/machine_memory.hpp"

namespace odeskin {
namespace {

// About 15 us of normals at 4 ns a vertex: enough work per task that scheduling is noise.
constexpr std::size_t kVertexChunk = 4096;

std::size_t chunkCount(std::size_t vertices) { return (vertices + kVertexChunk - 1) / kVertexChunk; }

}  // namespace

Result<CpuRuntime> CpuRuntime::create(const RuntimeAsset& asset, const RuntimeOptions& options) {
  ODESKIN_TRY(checkOptions(asset, options));
  const std::size_t v = asset.vertexCount();
  const std::size_t limit = std::numeric_limits<std::size_t>::max() / sizeof(gpu::Float4) / 2;
  if (v != 0 && std::size_t{options.capacity} * options.frames_in_flight > limit / v) {
    return outOfRange("cpu runtime: capacity " + std::to_string(options.capacity) + " x " + std::to_string(v) +
                      " vertices does not fit in memory");
  }
  // The frames' outputs dominate; 1,048,576 instances of a 420-vertex asset asked for 27 GB on a
  // 23 GB machine, and the kernel killed the process while the buffers were zeroed.
  // Render vertices are gathered into arrays of their own, beside the topology's.
  const std::size_t r = odeskin::gathersRenderVertices(asset, options) ? asset.renderVertexCount() : 0;
  if (r != 0 && std::size_t{options.capacity} * options.frames_in_flight > limit / r) {
    return outOfRange("cpu runtime: capacity " + std::to_string(options.capacity) + " x " + std::to_string(r) +
                      " render vertices does not fit in memory");
  }
  // In double: the product of instances and bytes per instance can pass 2^64, and a wrapped count
  // once let an impossible size through to the allocations.
  const double tangent_bytes = options.tangents ? double(asset.renderVertexCount()) * sizeof(gpu::Float4) : 0.0;
  const double output_bytes = double(options.frames_in_flight) * options.capacity *
                              (double(v + r) * sizeof(gpu::Float4) * (options.normals ? 2 : 1) + tangent_bytes);
  constexpr double kMaxBytes = 18446744073709549568.0;  // the largest double below 2^64
  const std::uint64_t bytes = output_bytes < kMaxBytes ? static_cast<std::uint64_t>(output_bytes) : UINT64_MAX;
  ODESKIN_TRY(checkFitsInMemory(bytes, physicalMemoryBytes(),
                                "cpu runtime: the output buffers of " + std::to_string(options.frames_in_flight) +
                                    " frames of " + std::to_string(options.capacity) + " instances x " +
                                    std::to_string(v) + " vertices" +
                                    (r != 0 ? " (and " + std::to_string(r) + " render vertices)" : std::string()),
                                "lower the capacity or the frames in flight"));
  // The machine may have the memory while this process may not (ulimit -v, a container's limit):
  // the allocations then throw, which is a failure to report, not an abort.
  try {
    CpuRuntime rt(asset, options);
    for (std::uint32_t p = 0; p < asset.presetCount(); ++p) {
      ODESKIN_ASSIGN_OR_RETURN(CpuDeformKernel deformer, CpuDeformKernel::create(asset.packed(p)));
      rt.deformers_.push_back(std::move(deformer));
    }
    rt.records_.resize(options.capacity);
    rt.bones_.resize(std::size_t{options.capacity} * asset.boneCount());
    rt.basis_.resize(std::size_t{options.capacity} * asset.basisEntries());
    rt.slots_.resize(options.frames_in_flight);
    rt.chunk_bounds_.resize(std::size_t{std::min(options.capacity, rt.arena().threads())} * chunkCount(v));
    for (Slot& slot : rt.slots_) {
      slot.positions.resize(std::size_t{options.capacity} * v);
      // Across hard edges the render vertices' normals are computed directly, from the positions.
      if (options.normals && !rt.computesRenderNormals()) slot.normals.resize(slot.positions.size());
      slot.bounds.resize(options.capacity);
      if (r != 0) {
        slot.render_positions.resize(std::size_t{options.capacity} * r);
        if (options.normals) slot.render_normals.resize(slot.render_positions.size());
      }
      if (options.tangents) slot.tangents.resize(std::size_t{options.capacity} * asset.renderVertexCount());
    }
    return rt;
  } catch (const std::bad_alloc&) {
    return outOfRange("cpu runtime: " + std::to_string(options.capacity) + " instances x " + std::to_string(v) +
                      " vertices in " + std::to_string(options.frames_in_flight) +
                      " frames do not fit in this process's memory; lower the capacity or the frames in flight");
  }
}

Status CpuRuntime::submitSlot(std::uint32_t slot_index, std::uint32_t instance_count, FrameTimes& times) {
  const auto start = std::chrono::steady_clock::now();
  prepareInputs(std::span(records_).first(instance_count),
                std::span(bones_).first(std::size_t{instance_count} * asset().boneCount()),
                std::span(basis_).first(std::size_t{instance_count} * asset().basisEntries()));
  const auto prepared = std::chrono::steady_clock::now();
  times.prepare_seconds = std::chrono::duration<double>(prepared - start).count();

  Slot& slot = slots_[slot_index];
  // Whole rounds of one instance per thread, then the remainder (fewer instances than threads)
  // spread over all of them, so that no thread idles through a last, part-filled round.
  const std::uint32_t whole = instance_count - instance_count % arena().threads();
  Status status = deformInstances(slot, 0, whole, 1, true);
  Status rest = deformSpread(slot, whole, instance_count);
  if (status.ok()) status = std::move(rest);
  slot.instance_count = instance_count;
  times.deform_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - prepared).count();
  return status;
}

Status CpuRuntime::deformInstance(Slot& slot, std::size_t k, unsigned threads) {
  const std::size_t v = asset().vertexCount();
  const std::size_t b = asset().boneCount();
  const std::size_t e = asset().basisEntries();
  const gpu::InstanceRecord& r = records_[k];
  Status status = deformers_[r.preset].deform(r.segment, std::span(bones_).subspan(k * b, b),
                                              std::span(basis_).subspan(k * e, e),
                                              std::span(slot.positions).subspan(k * v, v), threads);
  if (status.ok()) return status;
  return Status(status.code(), "cpu runtime: instance " + std::to_string(k) + ": " + status.message());
}

Status CpuRuntime::deformInstances(Slot& slot, std::uint32_t first, std::uint32_t end, unsigned threads, bool outputs) {
  const std::size_t v = asset().vertexCount();
  std::mutex error_mutex;
  Status first_error;
  arena().parallelFor(end - first, 1, [&](std::size_t begin_task, std::size_t end_task) {
    for (std::size_t k = first + begin_task; k < first + end_task; ++k) {
      Status status = deformInstance(slot, k, threads);
      if (!status.ok()) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (first_error.ok()) first_error = std::move(status);
        continue;
      }
      if (!outputs) continue;
      const std::span<const gpu::Float4> out = std::span(slot.positions).subspan(k * v, v);
      if (!slot.normals.empty()) {
        computeVertexNormals(asset().cornerOffsets(), asset().corners(), out, std::span(slot.normals).subspan(k * v, v));
      }
      slot.bounds[k] = computeBounds(out);
      if (finishes()) finishInstance(slot, k, 0, outputVertexCount());
    }
  });
  return first_error;
}

void CpuRuntime::finishInstance(Slot& slot, std::size_t k, std::size_t begin, std::size_t end) const {
  const std::size_t v = asset().vertexCount();
  const std::size_t r = outputVertexCount();
  const std::span<const gpu::Float4> positions = std::span<const gpu::Float4>(slot.positions).subspan(k * v, v);
  const std::span<const gpu::Float4> normals =
      slot.normals.empty() ? std::span<const gpu::Float4>() : std::span<const gpu::Float4>(slot.normals).subspan(k * v, v);
  if (gathersRenderVertices()) {
    const std::span<const std::uint32_t> topology = asset().renderTopology();
    const std::span<gpu::Float4> render_normals =
        slot.render_normals.empty() ? std::span<gpu::Float4>() : std::span(slot.render_normals).subspan(k * r, r);
    gatherRenderVertices(topology, positions, std::span(slot.render_positions).subspan(k * r, r), begin, end);
    if (!normals.empty()) gatherRenderVertices(topology, normals, render_normals, begin, end);
    if (computesRenderNormals()) {
      computeRenderNormals(asset().renderCornerOffsets(), asset().renderCorners(), topology, positions, render_normals,
                           begin, end);
    }
  }
  if (!slot.tangents.empty()) {
    // Each tangent is made orthogonal to its own output vertex's normal (a hard edge's side's).
    const std::span<const gpu::Float4> out_normals =
        gathersRenderVertices() ? std::span<const gpu::Float4>(slot.render_normals).subspan(k * r, r) : normals;
    computeVertexTangents(asset().tangentTables(), positions, out_normals, std::span(slot.tangents).subspan(k * r, r),
                          begin, end);
  }
}

Status CpuRuntime::deformSpread(Slot& slot, std::uint32_t first, std::uint32_t end) {
  if (first == end) return okStatus();
  // threads 0: each instance's deformation splits over this arena (called from inside it).
  ODESKIN_TRY(deformInstances(slot, first, end, 0, false));
  const std::size_t v = asset().vertexCount();
  const std::size_t chunks = chunkCount(v);
  arena().parallelFor((end - first) * chunks, 1, [&](std::size_t begin_job, std::size_t end_job) {
    for (std::size_t job = begin_job; job < end_job; ++job) {
      const std::size_t k = first + job / chunks;
      const std::size_t from = (job % chunks) * kVertexChunk;
      const std::size_t to = std::min(from + kVertexChunk, v);
      const std::span<const gpu::Float4> out = std::span(slot.positions).subspan(k * v, v);
      if (!slot.normals.empty()) {
        computeVertexNormals(asset().cornerOffsets(), asset().corners(), out, std::span(slot.normals).subspan(k * v, v),
                             from, to);
      }
      chunk_bounds_[job] = computeBounds(out.subspan(from, to - from));
    }
  });
  for (std::size_t k = first; k < end; ++k) {
    InstanceBounds bounds;
    for (std::size_t c = 0; c < chunks; ++c) bounds.merge(chunk_bounds_[(k - first) * chunks + c]);
    slot.bounds[k] = bounds;
  }
  if (!finishes()) return okStatus();
  // After every normal of the instances: a render vertex may copy any topology vertex, and a
  // tangent reads its vertex's normal.
  const std::size_t r = outputVertexCount();
  const std::size_t render_chunks = chunkCount(r);
  arena().parallelFor((end - first) * render_chunks, 1, [&](std::size_t begin_job, std::size_t end_job) {
    for (std::size_t job = begin_job; job < end_job; ++job) {
      const std::size_t from = (job % render_chunks) * kVertexChunk;
      finishInstance(slot, first + job / render_chunks, from, std::min(from + kVertexChunk, r));
    }
  });
  return okStatus();
}

Result<std::span<const gpu::Float4>> CpuRuntime::positions(std::uint64_t frame) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, heldSlot(frame, "positions"));
  return std::span<const gpu::Float4>(slots_[slot].outPositions())
      .first(std::size_t{slots_[slot].instance_count} * outputVertexCount());
}

Result<std::span<const gpu::Float4>> CpuRuntime::normals(std::uint64_t frame) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, heldSlot(frame, "normals"));
  if (!options().normals) return std::span<const gpu::Float4>();
  return std::span<const gpu::Float4>(slots_[slot].outNormals())
      .first(std::size_t{slots_[slot].instance_count} * outputVertexCount());
}

Result<std::span<const gpu::Float4>> CpuRuntime::tangents(std::uint64_t frame) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, heldSlot(frame, "tangents"));
  return std::span<const gpu::Float4>(slots_[slot].tangents)
      .first(slots_[slot].tangents.empty() ? 0 : std::size_t{slots_[slot].instance_count} * outputVertexCount());
}

Status CpuRuntime::copyPositions(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) {
  const std::size_t v = outputVertexCount();
  std::copy_n(slots_[slot].outPositions().begin() + static_cast<std::ptrdiff_t>(instance * v), v, out.begin());
  return okStatus();
}

Status CpuRuntime::copyNormals(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) {
  const std::size_t v = outputVertexCount();
  std::copy_n(slots_[slot].outNormals().begin() + static_cast<std::ptrdiff_t>(instance * v), v, out.begin());
  return okStatus();
}

Status CpuRuntime::copyTangents(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) {
  const std::size_t v = outputVertexCount();
  std::copy_n(slots_[slot].tangents.begin() + static_cast<std::ptrdiff_t>(instance * v), v, out.begin());
  return okStatus();
}

RuntimeMemory CpuRuntime::memory() const {
  RuntimeMemory m;
  m.capacity = capacity();
  for (const CpuDeformKernel& kernel : deformers_) m.asset += kernel.stats().bytes;
  m.inputs = instanceStateBytes() + reservedBytes(records_) + reservedBytes(bones_) + reservedBytes(basis_) +
             reservedBytes(chunk_bounds_);
  for (const Slot& slot : slots_) {
    m.outputs += reservedBytes(slot.positions) + reservedBytes(slot.normals) + reservedBytes(slot.bounds) +
                 reservedBytes(slot.render_positions) + reservedBytes(slot.render_normals) + reservedBytes(slot.tangents);
  }
  return m;
}

Status CpuRuntime::copyBounds(std::uint32_t slot, std::span<InstanceBounds> out) {
  std::copy_n(slots_[slot].bounds.begin(), out.size(), out.begin());
  return okStatus();
}

}  // namespace odeskin
