// SPDX-License-Identifier: MIT
// Plays a loaded DeformAsset at any global time t in [0, K-1] on the CPU (the double-precision
// reference job) or on Vulkan (packDeformAsset + GpuDeformer, float32), and maps the topology
// positions to the render layout when the asset has one.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "demo.hpp"
#include "engine/offline/deform_player.hpp"

namespace odeskin {

namespace vk {
struct Gpu;
}
class GpuDeformer;

struct PlaybackOptions {
  Backend backend = Backend::kCpu;  // kAuto: Vulkan when a device opens, else the CPU
  std::string device = "auto";      // Vulkan device selector (index or name substring)
  bool validation = false;          // Khronos validation layer; checkValidation() fails on any message
};

class AssetPlayback {
 public:
  // `asset` must stay alive and unchanged while the playback is used. Errors: DeformPlayer's
  // (a resonant material mode), kUnavailable when Vulkan is required but no device opens,
  // GpuDeformer::create's. kAuto falls back to the CPU when any Vulkan step fails (opening the
  // device, uploading the asset, or a frame later: out of memory, device lost); `notes` (optional,
  // must outlive the playback) hears about it once.
  static Result<AssetPlayback> create(const DeformAsset& asset, const PlaybackOptions& options, std::ostream* notes);

  AssetPlayback(AssetPlayback&&) noexcept;
  AssetPlayback& operator=(AssetPlayback&&) noexcept;
  ~AssetPlayback();

  // Topology positions at global time t (clamped to [0, K-1]); `out` is resized to V.
  Status positionsAt(double t, std::vector<Vec3>& out);

  // "cpu: double-precision reference" or "vulkan: <device name>".
  const std::string& device() const { return device_; }
  bool onGpu() const { return deformer_ != nullptr; }
  // kInternal when the validation layer reported messages (naming the count and the first one).
  Status checkValidation() const;

 private:
  AssetPlayback() = default;
  Status openGpu(const PlaybackOptions& options);
  void fallBack(const Status& why);  // drops the GPU objects and says so on notes_

  const DeformAsset* asset_ = nullptr;
  Backend backend_ = Backend::kCpu;
  std::ostream* notes_ = nullptr;
  std::optional<DeformPlayer> player_;
  std::string device_;
  // Heap-held so the deformer's reference to the device survives moves of this object; the
  // deformer is declared after the device so it is destroyed first.
  std::unique_ptr<vk::Gpu> gpu_;
  std::unique_ptr<GpuDeformer> deformer_;
  std::vector<ModeBasisValue> basis_;
  std::vector<BoneTransform> bones_;
  std::vector<gpu::ModeBasis> gpu_basis_;
  std::vector<gpu::BoneMatrix> gpu_bones_;
  std::vector<gpu::Float4> gpu_out_;
};

}  // namespace odeskin
