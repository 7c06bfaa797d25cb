// SPDX-License-Identifier: MIT
#include "asset_playback.hpp"

#include <ostream>

#include "host/gpu_deformer.hpp"

namespace odeskin {

AssetPlayback::AssetPlayback(AssetPlayback&&) noexcept = default;
AssetPlayback& AssetPlayback::operator=(AssetPlayback&&) noexcept = default;
AssetPlayback::~AssetPlayback() = default;

Result<AssetPlayback> AssetPlayback::create(const DeformAsset& asset, const PlaybackOptions& options,
                                            std::ostream* notes) {
  AssetPlayback playback;
  playback.asset_ = &asset;
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(asset));
  playback.player_.emplace(std::move(player));
  playback.basis_.resize(playback.player_->basisSize());
  playback.bones_.resize(asset.bone_count);
  playback.device_ = "cpu: double-precision reference";
  if (options.backend == Backend::kCpu) return playback;

  playback.backend_ = options.backend;
  playback.notes_ = notes;
  if (Status s = playback.openGpu(options); !s.ok()) {
    if (options.backend == Backend::kVulkan) return s;
    playback.fallBack(s);
  }
  return playback;
}

Status AssetPlayback::openGpu(const PlaybackOptions& options) {
  ODESKIN_ASSIGN_OR_RETURN(vk::Gpu gpu, vk::Gpu::open(options.device, options.validation));
  gpu_ = std::make_unique<vk::Gpu>(std::move(gpu));
  ODESKIN_ASSIGN_OR_RETURN(PackedDeformData packed, packDeformAsset(*asset_));
  ODESKIN_ASSIGN_OR_RETURN(GpuDeformer deformer, GpuDeformer::create(gpu_->device, packed));
  deformer_ = std::make_unique<GpuDeformer>(std::move(deformer));
  device_ = std::string("vulkan: ") + gpu_->device.name();
  gpu_basis_.resize(basis_.size());
  gpu_bones_.resize(bones_.size());
  gpu_out_.resize(asset_->vertexCount());
  return okStatus();
}

void AssetPlayback::fallBack(const Status& why) {
  // The deformer before the device it was built on.
  deformer_.reset();
  gpu_.reset();
  device_ = "cpu: double-precision reference";
  if (notes_) *notes_ << "note: Vulkan failed (" << why.message() << "); playing on the CPU\n";
}

Status AssetPlayback::positionsAt(double t, std::vector<Vec3>& out) {
  const auto [segment, tau] = player_->locate(t);
  player_->basisAt(tau, basis_);
  player_->bonesAt(*asset_, segment, tau, bones_);
  out.resize(asset_->vertexCount());
  if (!deformer_) return referenceJob(*asset_, segment, basis_, bones_, out).run();
  toGpuBasis(basis_, gpu_basis_);
  toGpuBones(bones_, gpu_bones_);
  Status ran = deformer_->run(GpuDeformFrame{segment, gpu_bones_, gpu_basis_});
  if (ran.ok()) ran = deformer_->readPositions(gpu_out_);
  if (!ran.ok()) {
    // --backend auto: a device lost or out of memory mid-sequence finishes the frames on the CPU.
    if (backend_ != Backend::kAuto) return ran;
    fallBack(ran);
    return referenceJob(*asset_, segment, basis_, bones_, out).run();
  }
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec3(gpu_out_[i].x, gpu_out_[i].y, gpu_out_[i].z);
  return okStatus();
}

Status AssetPlayback::checkValidation() const {
  if (!gpu_ || !gpu_->instance.validationEnabled() || gpu_->instance.debugLog().count() == 0) return okStatus();
  return internalError("the Vulkan validation layer reported " + std::to_string(gpu_->instance.debugLog().count()) +
                       " message(s); first: " + gpu_->instance.debugLog().messages().front());
}

}  // namespace odeskin
