// SPDX-License-Identifier: MIT
// The runtime API an engine drives every frame (issue 6 point 1), shared by CpuRuntime (here) and
// VulkanRuntime (host/runtime): load a RuntimeAsset once, hold up to `capacity` instances, each with
// its own time (or segment and local time), bones (the engine's, or interpolated from the asset's
// key poses) and material preset; submitFrame() deforms every instance into one output array per
// frame (instance k's vertices at k * V; with render_layout, a glTF asset's render vertices), with
// recomputed normals (and, on request, tangents) and per-instance bounding boxes.
//
// Frames and buffering: submitFrame() returns the frame's number (1, 2, ...). The outputs of the
// last framesInFlight() frames stay readable: frame k's live in slot (k - 1) % framesInFlight(), so
// a renderer can draw frame k while frame k + 1 is deformed. Readers wait for their frame.
//
// Threading: one thread at a time calls the methods of a runtime (they are not synchronised); the
// runtime itself spreads work over its WorkerArena (options.threads). No method allocates after
// create() except error messages; nothing throws.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "../core/result.hpp"
#include "instance_outputs.hpp"
#include "runtime_asset.hpp"
#include "worker_arena.hpp"

namespace odeskin {

// Each frame in flight holds a slot of outputs and bookkeeping; an engine keeps two or three. The
// bound keeps a typo (UINT32_MAX) from asking for gigabytes of slots before any output is sized.
inline constexpr std::uint32_t kMaxFramesInFlight = 256;

struct RuntimeOptions {
  std::uint32_t capacity = 1;          // most instances per frame; every buffer is sized for it once
  std::uint32_t frames_in_flight = 2;  // frames whose outputs stay readable (1..kMaxFramesInFlight); Vulkan runs that many at once
  bool normals = true;                 // recompute vertex normals every frame
  // Outputs in the asset's render vertices (RuntimeAsset::renderTopology: glTF input split at UV
  // and normal seams) instead of its topology vertices, so they bind beside the glTF's own UVs.
  // The deformation, normals and bounds are the topology's, copied to each render vertex, except
  // the normals across an asset's hard edges (RuntimeAssetOptions::render_normals), which are
  // each side's own; an asset without a render layout (OBJ input) outputs the same either way.
  bool render_layout = false;
  // Tangents for normal mapping every frame: the asset's bind tangents
  // (RuntimeAssetOptions::render_tangents) carried through the deformation and made orthogonal to
  // the recomputed normals (instance_tangents.hpp). Needs normals, and a render layout on an asset
  // that has one, since tangents belong to render vertices.
  bool tangents = false;
  unsigned threads = 0;                // host threads for preparing inputs (and the CPU backend's deformation); 0 = all;
                                       // capped at the machine's (WorkerArena)
};

// Whether `options` on `asset` gather the outputs into render vertices: a render layout asked for,
// on an asset whose render vertices differ from its topology's (glTF input).
inline bool gathersRenderVertices(const RuntimeAsset& asset, const RuntimeOptions& options) {
  return options.render_layout && !asset.renderTopology().empty();
}

// Local time of one segment: segment s < segmentCount() from key s to s + 1, tau in [0, 1].
struct SegmentTime {
  std::uint32_t segment = 0;
  double tau = 0.0;
};

struct InstanceState {
  // Global time in key units, [0, segmentCount()]: plays segment floor(t) at tau = t - floor(t)
  // (the end plays the last segment at tau = 1), as DeformPlayer::locate. Used when segment_time
  // is empty. Looping or ping-pong is the engine's arithmetic (seconds / asset.segmentSeconds()).
  double time = 0.0;
  std::optional<SegmentTime> segment_time;
  // Empty: bones interpolated from the asset's key poses at the instance's time (C1 key paths).
  // Else boneCount() matrices, bind space -> pose space, from the engine's own animation
  // (world placement included if it wants world-space output); copied by setInstance.
  std::span<const gpu::BoneMatrix> bones;
  std::uint32_t preset = 0;  // material preset, < asset.presetCount() (0: the asset's own materials)

  // Builders, so call sites read InstanceState::atTime(t).withPreset(1) (brace-initialising some
  // fields trips -Wmissing-field-initializers).
  static InstanceState atTime(double t) {
    InstanceState s;
    s.time = t;
    return s;
  }
  static InstanceState atSegment(std::uint32_t segment, double tau) {
    InstanceState s;
    s.segment_time = SegmentTime{segment, tau};
    return s;
  }
  InstanceState withBones(std::span<const gpu::BoneMatrix> engine_bones) const {
    InstanceState s = *this;
    s.bones = engine_bones;
    return s;
  }
  InstanceState withPreset(std::uint32_t material_preset) const {
    InstanceState s = *this;
    s.preset = material_preset;
    return s;
  }
};

// Host and device time of one frame, in seconds.
struct FrameTimes {
  double prepare_seconds = 0.0;  // host: every instance's segment, time basis and bones
  double submit_seconds = 0.0;   // host: the whole submitFrame() call (prepare included)
  // CPU backend: wall time of deforming, normals and bounds (inside submit_seconds). Vulkan: GPU
  // time between the frame's timestamp queries (0 when the queue has no timestamps).
  double deform_seconds = 0.0;
};

// Memory a runtime holds, in bytes, so that an engine can budget its characters' deformation (as
// Unreal budgets its skin cache) and see what one more instance of capacity costs. Host arrays
// count at their reserved size, GPU buffers at their allocations' (each rounded up to the device's
// alignment); pipelines, descriptor sets and query pools (a few KiB) are left out. The RuntimeAsset
// is the caller's and is not counted: runtimes may share one.
struct RuntimeMemory {
  std::uint32_t capacity = 0;
  std::uint64_t asset = 0;    // prepared from the asset once: the CPU kernels' blocks, or the uploaded arrays
  std::uint64_t inputs = 0;   // the instances' states and their frame inputs (Vulkan: every slot's, and the folded series)
  std::uint64_t outputs = 0;  // every slot's positions, normals, tangents, render-vertex copies and bounds
  std::uint64_t device_local = 0;  // of the total, in device-local GPU memory (0 on the CPU backend)

  std::uint64_t total() const { return asset + inputs + outputs; }
  // Inputs and outputs per instance of capacity: nearly all of both grows with it.
  double perInstance() const { return capacity == 0 ? 0.0 : static_cast<double>(inputs + outputs) / capacity; }
};

// A host array's share of RuntimeMemory.
template <typename T>
std::uint64_t reservedBytes(const std::vector<T>& array) {
  return std::uint64_t{array.capacity()} * sizeof(T);
}

class DeformRuntime {
 public:
  virtual ~DeformRuntime() = default;
  DeformRuntime(const DeformRuntime&) = delete;
  DeformRuntime& operator=(const DeformRuntime&) = delete;

  // Not of a runtime moved from (it has no asset); the counts below are 0 there.
  const RuntimeAsset& asset() const { return *asset_; }
  const RuntimeOptions& options() const { return options_; }
  std::uint32_t capacity() const { return options_.capacity; }
  std::uint32_t framesInFlight() const { return options_.frames_in_flight; }
  std::uint32_t instanceCount() const { return instance_count_; }
  // Vertices per instance in the outputs (readPositions, frame buffers): the asset's render
  // vertices with options().render_layout, else its topology vertices.
  std::uint32_t outputVertexCount() const {
    if (asset_ == nullptr) return 0;
    return options_.render_layout ? asset_->renderVertexCount() : asset_->vertexCount();
  }
  // Whether the outputs are gathered from the topology's (a render layout that differs from it).
  bool gathersRenderVertices() const { return asset_ != nullptr && odeskin::gathersRenderVertices(*asset_, options_); }
  // Whether the normals are computed per render vertex (hard edges: RuntimeAsset::hasHardEdges)
  // rather than per topology vertex and gathered.
  bool computesRenderNormals() const { return gathersRenderVertices() && options_.normals && asset_->hasHardEdges(); }
  std::uint64_t lastFrame() const { return last_frame_; }
  virtual std::string_view backendName() const = 0;

  // Instances [0, count) take part in the next frames; new ones start at time 0, interpolated
  // bones, preset 0. kInvalidArgument when count > capacity().
  Status setInstanceCount(std::uint32_t count);
  // Sets instance `index` for the next submitFrame(). kInvalidArgument, naming the instance and the
  // problem, for an index >= instanceCount(), a non-finite or out-of-range time, segment or tau, a
  // bones span that is neither empty nor boneCount() long or holds a non-finite entry, or a preset
  // >= presetCount(). A rejected call leaves the instance as it was.
  Status setInstance(std::uint32_t index, const InstanceState& state);

  // Deforms every instance in its current state; returns the frame's number. Waits first for the
  // frame that last used this frame's slot (framesInFlight() frames ago). Backend errors only
  // (and, on Vulkan, a slot still held by a recorded frame: VulkanRuntime::recordFrame).
  Result<std::uint64_t> submitFrame();
  // Waits for every submitted frame.
  virtual Status wait() = 0;

  // Outputs of `frame`, one of the last framesInFlight() submitted (kInvalidArgument otherwise,
  // naming the frames held), for `instance` < that frame's instance count; each waits for the frame.
  // `out` has exactly outputVertexCount() entries (kInvalidArgument otherwise).
  Status readPositions(std::uint64_t frame, std::uint32_t instance, std::span<gpu::Float4> out);
  // kInvalidArgument when options().normals is false.
  Status readNormals(std::uint64_t frame, std::uint32_t instance, std::span<gpu::Float4> out);
  // xyz the unit tangent, w its handedness. kInvalidArgument when options().tangents is false.
  Status readTangents(std::uint64_t frame, std::uint32_t instance, std::span<gpu::Float4> out);
  // One box per instance of the frame: `out` has exactly that frame's instance count.
  Status readBounds(std::uint64_t frame, std::span<InstanceBounds> out);
  Result<FrameTimes> frameTimes(std::uint64_t frame);
  // What this runtime holds now; constant after create() (nothing is allocated per frame).
  virtual RuntimeMemory memory() const = 0;

 protected:
  // kInvalidArgument for frames_in_flight = 0, or tangents on an asset without them, without
  // normals, or without the render layout of an asset that has one; kOutOfRange for frames_in_flight
  // above kMaxFramesInFlight (other limits are the backends').
  static Status checkOptions(const RuntimeAsset& asset, const RuntimeOptions& options);
  DeformRuntime(const RuntimeAsset& asset, const RuntimeOptions& options);
  // A runtime moved from is empty (capacity 0, no instances, no frames): calls on it return
  // kInvalidArgument saying so, where the counts it kept used to index arrays it no longer had.
  DeformRuntime(DeformRuntime&& other) noexcept;
  DeformRuntime& operator=(DeformRuntime&& other) noexcept;

  // Writes what instances [0, instanceCount()) play this frame: `records` (instanceCount()),
  // `bones` (instanceCount() x B), `basis` (instanceCount() x basisEntries()), on the arena.
  void prepareInputs(std::span<gpu::InstanceRecord> records, std::span<gpu::BoneMatrix> bones,
                     std::span<gpu::ModeBasis> basis) const;
  const WorkerArena& arena() const { return arena_; }
  // Host bytes of the instances' states (the backends' memory() counts them as inputs).
  std::uint64_t instanceStateBytes() const;

  // Backends: deform instanceCount() instances into `slot`, preparing the inputs with
  // prepareInputs, and store its host times. Frame bookkeeping is the base's.
  virtual Status submitSlot(std::uint32_t slot, std::uint32_t instance_count, FrameTimes& times) = 0;
  virtual Status waitSlot(std::uint32_t slot) = 0;
  // Whether `slot` may take a new frame now, checked before its old frame is given up (a Vulkan
  // frame recorded into an engine's command buffer keeps its slot until the engine completes it).
  virtual Status checkSlotFree(std::uint32_t /*slot*/) const { return okStatus(); }
  // Copies from the finished slot. Sizes and indices are checked already.
  virtual Status copyPositions(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) = 0;
  virtual Status copyNormals(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) = 0;
  virtual Status copyTangents(std::uint32_t slot, std::uint32_t instance, std::span<gpu::Float4> out) = 0;
  virtual Status copyBounds(std::uint32_t slot, std::span<InstanceBounds> out) = 0;
  // GPU seconds of the finished slot (Vulkan); the CPU backend's deform time is in its FrameTimes.
  virtual double deviceSeconds(std::uint32_t slot) const = 0;

  // The slot of `frame`, or kInvalidArgument naming the frames held; slotOf does not wait,
  // heldSlot waits for the frame to finish (waitSlot).
  Result<std::uint32_t> slotOf(std::uint64_t frame, const char* what) const;
  Result<std::uint32_t> heldSlot(std::uint64_t frame, const char* what);

 private:
  struct Instance {
    std::uint32_t segment = 0;
    double tau = 0.0;
    std::uint32_t preset = 0;
    bool engine_bones = false;
  };
  struct Slot {
    std::uint64_t frame = 0;  // 0: never used
    std::uint32_t instance_count = 0;
    FrameTimes times;
  };
  Result<std::uint32_t> checkRead(std::uint64_t frame, std::uint32_t instance, std::size_t out_size, const char* what);
  Status checkNotMovedFrom(const char* what) const;
  void takeFrom(DeformRuntime& other) noexcept;

  const RuntimeAsset* asset_ = nullptr;
  RuntimeOptions options_;
  WorkerArena arena_;
  std::uint32_t instance_count_ = 0;
  std::uint64_t last_frame_ = 0;
  std::vector<Instance> instances_;            // capacity
  std::vector<gpu::BoneMatrix> engine_bones_;  // capacity x B: bones given by setInstance
  std::vector<Slot> slots_;                    // frames_in_flight
};

}  // namespace odeskin
