// SPDX-License-Identifier: MIT
#include "deform_runtime.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "../core/number_text.hpp"

namespace odeskin {
namespace {

// Instances per preparation task: each costs B key-path evaluations (a squad and a Hermite cubic).
constexpr std::size_t kPrepareGrain = 16;

std::string instanceName(std::uint32_t index) { return "runtime: instance " + std::to_string(index); }

// Exact: nine digits printed a time one ulp past the end as the end itself ("time 4 is outside [0, 4]").
std::string number(double value) { return std::isnan(value) ? "NaN" : exactText(value); }

bool finiteBone(const gpu::BoneMatrix& m) {
  for (const gpu::Float4& r : {m.row0, m.row1, m.row2}) {
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z) || !std::isfinite(r.w)) return false;
  }
  return true;
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

Status DeformRuntime::checkOptions(const RuntimeAsset& asset, const RuntimeOptions& options) {
  if (options.frames_in_flight == 0) return invalidArgument("runtime: frames_in_flight must be at least 1");
  if (options.frames_in_flight > kMaxFramesInFlight) {
    return outOfRange("runtime: frames_in_flight " + std::to_string(options.frames_in_flight) + " is above " +
                      std::to_string(kMaxFramesInFlight));
  }
  if (!options.tangents) return okStatus();
  if (!asset.hasTangents()) {
    return invalidArgument("runtime: tangents asked for, but the asset has none (RuntimeAssetOptions::render_tangents)");
  }
  if (!options.normals) return invalidArgument("runtime: tangents need normals (RuntimeOptions::normals)");
  if (!options.render_layout && !asset.renderTopology().empty()) {
    return invalidArgument("runtime: the asset's tangents are its render vertices'; tangents need "
                           "RuntimeOptions::render_layout on an asset with a render layout");
  }
  return okStatus();
}

DeformRuntime::DeformRuntime(const RuntimeAsset& asset, const RuntimeOptions& options)
    : asset_(&asset), options_(options), arena_(options.threads) {
  instances_.resize(options.capacity);
  engine_bones_.resize(static_cast<std::size_t>(options.capacity) * asset.boneCount());
  slots_.resize(options.frames_in_flight);
}

DeformRuntime::DeformRuntime(DeformRuntime&& other) noexcept : arena_(std::move(other.arena_)) { takeFrom(other); }

DeformRuntime& DeformRuntime::operator=(DeformRuntime&& other) noexcept {
  if (this != &other) {
    arena_ = std::move(other.arena_);
    takeFrom(other);
  }
  return *this;
}

// Everything but the arena, which the move constructor must initialise itself.
void DeformRuntime::takeFrom(DeformRuntime& other) noexcept {
  asset_ = std::exchange(other.asset_, nullptr);
  options_ = other.options_;  // plain values: the copy cannot throw
  other.options_.capacity = 0;
  instance_count_ = std::exchange(other.instance_count_, 0);
  last_frame_ = std::exchange(other.last_frame_, 0);
  instances_ = std::move(other.instances_);
  engine_bones_ = std::move(other.engine_bones_);
  slots_ = std::move(other.slots_);
  other.instances_.clear();
  other.engine_bones_.clear();
  other.slots_.clear();
}

Status DeformRuntime::checkNotMovedFrom(const char* what) const {
  if (asset_ != nullptr) return okStatus();
  return invalidArgument(std::string("runtime: ") + what + ": this runtime was moved from; use the one it was moved to");
}

Status DeformRuntime::setInstanceCount(std::uint32_t count) {
  ODESKIN_TRY(checkNotMovedFrom("setInstanceCount"));
  if (count > options_.capacity) {
    return invalidArgument("runtime: instance count " + std::to_string(count) + " exceeds the capacity " +
                           std::to_string(options_.capacity));
  }
  for (std::uint32_t k = instance_count_; k < count; ++k) instances_[k] = Instance{};
  instance_count_ = count;
  return okStatus();
}

Status DeformRuntime::setInstance(std::uint32_t index, const InstanceState& state) {
  ODESKIN_TRY(checkNotMovedFrom("setInstance"));
  if (index >= instance_count_) {
    return invalidArgument(instanceName(index) + " is out of range: the runtime has " +
                           std::to_string(instance_count_) + " instances (setInstanceCount)");
  }
  const RuntimeAsset& a = *asset_;
  Instance next;
  if (state.segment_time) {
    const SegmentTime& st = *state.segment_time;
    if (st.segment >= a.segmentCount()) {
      return invalidArgument(instanceName(index) + ": segment " + std::to_string(st.segment) + " is out of range: " +
                             "the asset has " + std::to_string(a.segmentCount()) + " segments");
    }
    if (!(st.tau >= 0.0 && st.tau <= 1.0)) {
      return invalidArgument(instanceName(index) + ": tau " + number(st.tau) + " is outside [0, 1]");
    }
    next.segment = st.segment;
    next.tau = st.tau;
  } else {
    if (!std::isfinite(state.time)) {
      return invalidArgument(instanceName(index) + ": time is " + number(state.time));
    }
    if (state.time < 0.0 || state.time > a.endTime()) {
      return invalidArgument(instanceName(index) + ": time " + number(state.time) + " is outside [0, " +
                             number(a.endTime()) + "] (key units)");
    }
    std::tie(next.segment, next.tau) = a.locate(state.time);
  }
  if (state.preset >= a.presetCount()) {
    return invalidArgument(instanceName(index) + ": preset " + std::to_string(state.preset) + " is out of range: " +
                           "the asset has " + std::to_string(a.presetCount()) + " presets");
  }
  next.preset = state.preset;
  const std::size_t bone_count = a.boneCount();
  if (!state.bones.empty()) {
    if (state.bones.size() != bone_count) {
      return invalidArgument(instanceName(index) + ": " + std::to_string(state.bones.size()) +
                             " bone matrices, expected " + std::to_string(bone_count) + " (or none to interpolate)");
    }
    for (std::size_t b = 0; b < bone_count; ++b) {
      if (!finiteBone(state.bones[b])) {
        return invalidArgument(instanceName(index) + ": bone matrix " + std::to_string(b) + " has a non-finite entry");
      }
    }
    std::copy(state.bones.begin(), state.bones.end(), engine_bones_.begin() + static_cast<std::ptrdiff_t>(index * bone_count));
    next.engine_bones = true;
  }
  instances_[index] = next;
  return okStatus();
}

void DeformRuntime::prepareInputs(std::span<gpu::InstanceRecord> records, std::span<gpu::BoneMatrix> bones,
                                  std::span<gpu::ModeBasis> basis) const {
  const RuntimeAsset& a = *asset_;
  const std::size_t bone_count = a.boneCount();
  const std::size_t entries = a.basisEntries();
  arena_.parallelFor(instance_count_, kPrepareGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Instance& in = instances_[k];
      const PackedDeformData& packed = a.packed(in.preset);
      records[k] = gpu::InstanceRecord{in.segment, packed.remainder_base[in.segment], a.ratesOffset(in.preset), in.preset};
      a.basisAt(in.preset, in.tau, basis.subspan(k * entries, entries));
      std::span<gpu::BoneMatrix> out = bones.subspan(k * bone_count, bone_count);
      if (in.engine_bones) {
        std::copy_n(engine_bones_.begin() + static_cast<std::ptrdiff_t>(k * bone_count), bone_count, out.begin());
      } else {
        a.bonesAt(in.segment, in.tau, out);
      }
    }
  });
}

Result<std::uint64_t> DeformRuntime::submitFrame() {
  ODESKIN_TRY(checkNotMovedFrom("submitFrame"));
  const auto start = std::chrono::steady_clock::now();
  const std::uint32_t slot = static_cast<std::uint32_t>(last_frame_ % options_.frames_in_flight);
  FrameTimes times;
  ODESKIN_TRY(checkSlotFree(slot));
  // The slot's old frame is gone from here on, whether or not this submission succeeds.
  slots_[slot] = Slot{};
  ODESKIN_TRY(submitSlot(slot, instance_count_, times));
  times.submit_seconds = seconds(start);
  slots_[slot] = Slot{++last_frame_, instance_count_, times};
  return last_frame_;
}

Result<std::uint32_t> DeformRuntime::slotOf(std::uint64_t frame, const char* what) const {
  ODESKIN_TRY(checkNotMovedFrom(what));
  const std::uint64_t held = std::min<std::uint64_t>(last_frame_, options_.frames_in_flight);
  if (frame == 0 || frame > last_frame_ || frame + held <= last_frame_) {
    const std::string frames = held == 0 ? std::string("none submitted yet")
                                         : std::to_string(last_frame_ - held + 1) + ".." + std::to_string(last_frame_);
    return invalidArgument(std::string("runtime: ") + what + ": frame " + std::to_string(frame) +
                           " is not held (frames held: " + frames + ")");
  }
  const std::uint32_t slot = static_cast<std::uint32_t>((frame - 1) % options_.frames_in_flight);
  if (slots_[slot].frame != frame) {
    return invalidArgument(std::string("runtime: ") + what + ": frame " + std::to_string(frame) +
                           " has no outputs (a submission into its slot failed)");
  }
  return slot;
}

Result<std::uint32_t> DeformRuntime::heldSlot(std::uint64_t frame, const char* what) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, slotOf(frame, what));
  ODESKIN_TRY(waitSlot(slot));
  return slot;
}

Result<std::uint32_t> DeformRuntime::checkRead(std::uint64_t frame, std::uint32_t instance, std::size_t out_size,
                                               const char* what) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, heldSlot(frame, what));
  if (instance >= slots_[slot].instance_count) {
    return invalidArgument(std::string("runtime: ") + what + ": instance " + std::to_string(instance) +
                           " is out of range: frame " + std::to_string(frame) + " has " +
                           std::to_string(slots_[slot].instance_count) + " instances");
  }
  if (out_size != outputVertexCount()) {
    return invalidArgument(std::string("runtime: ") + what + ": out has " + std::to_string(out_size) +
                           " entries, expected the asset's " + std::to_string(outputVertexCount()) +
                           (options_.render_layout ? " render vertices" : " vertices"));
  }
  return slot;
}

Status DeformRuntime::readPositions(std::uint64_t frame, std::uint32_t instance, std::span<gpu::Float4> out) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, checkRead(frame, instance, out.size(), "readPositions"));
  return copyPositions(slot, instance, out);
}

Status DeformRuntime::readNormals(std::uint64_t frame, std::uint32_t instance, std::span<gpu::Float4> out) {
  if (!options_.normals) return invalidArgument("runtime: readNormals: the runtime was created with normals off");
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, checkRead(frame, instance, out.size(), "readNormals"));
  return copyNormals(slot, instance, out);
}

Status DeformRuntime::readTangents(std::uint64_t frame, std::uint32_t instance, std::span<gpu::Float4> out) {
  if (!options_.tangents) return invalidArgument("runtime: readTangents: the runtime was created with tangents off");
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, checkRead(frame, instance, out.size(), "readTangents"));
  return copyTangents(slot, instance, out);
}

Status DeformRuntime::readBounds(std::uint64_t frame, std::span<InstanceBounds> out) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, heldSlot(frame, "readBounds"));
  if (out.size() != slots_[slot].instance_count) {
    return invalidArgument("runtime: readBounds: out has " + std::to_string(out.size()) + " entries, frame " +
                           std::to_string(frame) + " has " + std::to_string(slots_[slot].instance_count) +
                           " instances");
  }
  return copyBounds(slot, out);
}

Result<FrameTimes> DeformRuntime::frameTimes(std::uint64_t frame) {
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t slot, heldSlot(frame, "frameTimes"));
  FrameTimes times = slots_[slot].times;
  const double device = deviceSeconds(slot);
  if (device > 0.0) times.deform_seconds = device;
  return times;
}

std::uint64_t DeformRuntime::instanceStateBytes() const {
  return reservedBytes(instances_) + reservedBytes(engine_bones_);
}

}  // namespace odeskin
